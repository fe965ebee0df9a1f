//! Server settings: address (loopback unless asked otherwise) and the limits that keep one
//! misbehaving page from hurting the simulation or the other pages.

use std::net::{IpAddr, Ipv4Addr, SocketAddr};

/// The loopback address the viewer listens on by default.
pub const DEFAULT_ADDR: IpAddr = IpAddr::V4(Ipv4Addr::LOCALHOST);
/// The default port.
pub const DEFAULT_PORT: u16 = 8080;

/// Server settings.
#[derive(Debug, Clone, PartialEq)]
pub struct ServerConfig {
    /// Where to listen (default 127.0.0.1:8080; port 0 picks a free port).
    pub addr: SocketAddr,
    /// Pages connected at once; one more is refused with HTTP 503 (default 8).
    pub max_clients: usize,
    /// Largest WebSocket message accepted, bytes; a larger one closes that connection (default
    /// 1024: the largest valid message is under 100 bytes).
    pub max_message_bytes: usize,
    /// Messages per second a page may send on average (burst: twice as many); the excess is
    /// refused with an error message (default 60).
    pub max_messages_per_second: u32,
    /// Malformed messages tolerated per connection before it is closed (default 16).
    pub max_malformed: u32,
}

impl Default for ServerConfig {
    fn default() -> Self {
        ServerConfig {
            addr: SocketAddr::new(DEFAULT_ADDR, DEFAULT_PORT),
            max_clients: 8,
            max_message_bytes: 1024,
            max_messages_per_second: 60,
            max_malformed: 16,
        }
    }
}
