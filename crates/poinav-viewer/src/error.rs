//! Errors of the viewer server.

/// What can go wrong starting or running the viewer.
#[derive(Debug, thiserror::Error)]
pub enum ViewerError {
    /// The address could not be bound.
    #[error("cannot listen on {addr}: {message}")]
    Bind {
        /// The address asked for.
        addr: std::net::SocketAddr,
        /// Why.
        message: String,
    },
    /// The simulation could not start (a robot overlapping a wall, an unknown target zone).
    #[error("simulation: {0}")]
    Simulation(#[from] poinav_sim::SimError),
    /// No place for the default robots.
    #[error("no room for the robots on floor `{floor}`: {message}")]
    Placement {
        /// The floor.
        floor: String,
        /// Why.
        message: String,
    },
    /// The server stopped with an I/O error.
    #[error("server: {0}")]
    Serve(String),
}
