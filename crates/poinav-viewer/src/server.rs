//! The HTTP and WebSocket server: the embedded page and scripts, the building as one GLB per
//! storey (`/api/model/<k>.glb`, listed in the scene's `model`), the
//! scene description, click-to-inspect data, and `/ws`, where pages receive every simulation
//! step and send key presses. Limits (clients, message size and rate, malformed messages) act
//! on the offending connection only; the simulation and the other pages go on.

use std::collections::BTreeMap;
use std::future::Future;
use std::net::SocketAddr;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;
use std::time::Instant;

use axum::body::Bytes;
use axum::extract::ws::{CloseFrame, Message, WebSocket, WebSocketUpgrade};
use axum::extract::{Path, State};
use axum::http::{header, HeaderMap, Method, StatusCode, Uri};
use axum::response::{IntoResponse, Response};
use axum::routing::get;
use axum::Router;
use serde_json::json;
use tokio::sync::broadcast::error::RecvError;

use crate::assets::asset;
use crate::config::ServerConfig;
use crate::error::ViewerError;
use crate::live::{Command, Live};
use crate::protocol::{parse_key, ClientMessage};
use crate::state::{ViewStorey, Viewer};
use poinav_nav::door_status::classified_status;
use poinav_nav::ObstacleKind;
use poinav_roles::RobotProfile;

/// WebSocket close code for a message over the size limit (RFC 6455 §7.4.1).
const CLOSE_TOO_BIG: u16 = 1009;
/// WebSocket close code for a policy violation.
const CLOSE_POLICY: u16 = 1008;

#[derive(Debug)]
struct App {
    config: ServerConfig,
    scene: String,
    model: Vec<Bytes>,
    elements: BTreeMap<String, String>,
    live: Live,
    clients: AtomicUsize,
}

/// A bound server, ready to run.
#[derive(Debug)]
pub struct Bound {
    listener: tokio::net::TcpListener,
    addr: SocketAddr,
    app: Arc<App>,
}

/// The robots' ray colours (clear, hit) by index: SPEC.md §4 gives Robot1 green/red and
/// Robot2 green/blue; further robots hit in orange.
fn ray_colours(i: usize) -> (&'static str, &'static str) {
    match i {
        0 => ("#22c55e", "#ef4444"),
        1 => ("#22c55e", "#3b82f6"),
        _ => ("#22c55e", "#f59e0b"),
    }
}

fn ring_json(ring: &[glam::DVec2]) -> Vec<[f64; 2]> {
    ring.iter().map(|p| [p.x, p.y]).collect()
}

/// One storey of the scene: its floor (bounds, doors with their passages and status, zones,
/// obstacle outlines for the cut view) and its robots with their start poses. A door's status
/// is the classification's for `profile` (the POI database's, what the simulation starts
/// from).
fn storey_json(s: &ViewStorey, profile: &RobotProfile) -> serde_json::Value {
    let robots: Vec<_> = s
        .robots
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let (clear, hit) = ray_colours(i);
            json!({
                "name": r.name,
                "length_m": r.profile.length_m,
                "width_m": r.profile.width_m,
                "keys": match i { 0 => Some("arrows"), 1 => Some("wasd"), _ => None },
                "ray_clear": clear,
                "ray_hit": hit,
                "start": [r.start.x, r.start.y],
                "heading_deg": r.heading_deg,
            })
        })
        .collect();
    let floor = &s.floor;
    let doors: Vec<_> = floor
        .doors
        .iter()
        .map(|d| {
            json!({
                "id": d.id,
                "name": d.name,
                "status": classified_status(d, profile).0.label(),
                "doorless": d.doorless,
                "center": [d.center.x, d.center.y],
                "ring": ring_json(&d.ring),
            })
        })
        .collect();
    let zones: Vec<_> = floor
        .zones
        .iter()
        .map(|z| {
            json!({
                "id": z.id,
                "name": z.name,
                "ring": ring_json(&z.ring),
                "roles": z.roles.iter().map(|r| r.label()).collect::<Vec<_>>(),
                "protocol": z.coordination.map(|c| c.1.label()),
                "min_separation_m": z.coordination.map(|c| c.0),
            })
        })
        .collect();
    // What the section plane cuts: walls, columns and the like drawn as filled outlines, so a
    // cut storey reads as a plan from above (a click on one inspects its element); other
    // obstacles' outlines too, for pages that draw them.
    let outlines = |structure: bool| -> Vec<serde_json::Value> {
        floor
            .obstacles
            .iter()
            .filter(|o| (o.kind == ObstacleKind::Structure) == structure)
            .flat_map(|o| {
                o.rings
                    .iter()
                    .filter(|r| r.len() >= 3)
                    .map(|r| json!({"id": o.id, "ring": ring_json(r)}))
            })
            .collect()
    };
    let bounds = floor
        .bounds()
        .map(|(lo, hi)| json!({"min": [lo.x, lo.y], "max": [hi.x, hi.y]}));
    json!({
        "storey": floor.name,
        "elevation_m": floor.elevation_m,
        "bounds": bounds,
        "robots": robots,
        "unplaced": s.unplaced,
        "doors": doors,
        "zones": zones,
        "structure": outlines(true),
        "obstacles": outlines(false),
    })
}

/// The scene: every storey ([`storey_json`]) and, at the top level, the one shown first (its
/// fields copied), with the title, the fixed step, the server's limits and the building's
/// parts (`model`: URL, storey index or null, name, elevation, elements and bytes of each).
fn scene_json(v: &Viewer, config: &ServerConfig) -> String {
    let storeys: Vec<_> = v
        .storeys
        .iter()
        .map(|s| storey_json(s, &v.options.poi_profile))
        .collect();
    let model: Vec<_> = v
        .model
        .iter()
        .enumerate()
        .map(|(k, c)| {
            json!({
                "url": format!("/api/model/{k}.glb"),
                "storey": c.storey,
                "name": c.name,
                "elevation_m": c.elevation_m,
                "elements": c.elements,
                "bytes": c.glb.len(),
            })
        })
        .collect();
    let mut scene = storeys.get(v.current).cloned().unwrap_or_else(|| json!({}));
    if let Some(o) = scene.as_object_mut() {
        o.insert("title".into(), json!(v.title));
        o.insert("source".into(), json!(v.source));
        o.insert("dt".into(), json!(v.options.dt));
        o.insert("current".into(), json!(v.current));
        o.insert("storeys".into(), json!(storeys));
        o.insert("model".into(), json!(model));
        o.insert(
            "limits".into(),
            json!({
                "max_clients": config.max_clients,
                "max_message_bytes": config.max_message_bytes,
                "max_messages_per_second": config.max_messages_per_second,
            }),
        );
    }
    scene.to_string()
}

/// Binds `config.addr` and starts the simulation of `viewer`; nothing is served until
/// [`Bound::run`].
pub async fn bind(config: ServerConfig, viewer: Viewer) -> Result<Bound, ViewerError> {
    let scene = scene_json(&viewer, &config);
    let elements = viewer
        .elements
        .iter()
        .map(|(k, v)| (k.clone(), serde_json::to_string(v).unwrap_or_default()))
        .collect();
    let storeys = viewer
        .storeys
        .into_iter()
        .map(|s| (s.floor, s.robots))
        .collect();
    let live = Live::start(storeys, viewer.current, viewer.options)?;
    let listener = tokio::net::TcpListener::bind(config.addr)
        .await
        .map_err(|e| ViewerError::Bind {
            addr: config.addr,
            message: e.to_string(),
        })?;
    let addr = listener.local_addr().map_err(|e| ViewerError::Bind {
        addr: config.addr,
        message: e.to_string(),
    })?;
    Ok(Bound {
        listener,
        addr,
        app: Arc::new(App {
            config,
            scene,
            model: viewer
                .model
                .into_iter()
                .map(|c| Bytes::from(c.glb))
                .collect(),
            elements,
            live,
            clients: AtomicUsize::new(0),
        }),
    })
}

impl Bound {
    /// The address it listens on (with the port chosen when 0 was asked for).
    pub fn local_addr(&self) -> SocketAddr {
        self.addr
    }

    /// A receiver of every following state the pages get (JSON text; a receiver that falls
    /// behind skips states, as a slow page does).
    pub fn subscribe(&self) -> tokio::sync::broadcast::Receiver<Arc<str>> {
        self.app.live.subscribe()
    }

    /// Serves until the process ends.
    pub async fn run(self) -> Result<(), ViewerError> {
        self.run_until(std::future::pending()).await
    }

    /// Serves until `shutdown` completes.
    pub async fn run_until(
        self,
        shutdown: impl Future<Output = ()> + Send + 'static,
    ) -> Result<(), ViewerError> {
        let router = Router::new()
            .route("/api/model/{file}", get(model))
            .route("/api/scene", get(scene))
            .route("/api/element/{guid}", get(element))
            .route("/ws", get(ws))
            .fallback(static_asset)
            .with_state(self.app);
        axum::serve(self.listener, router)
            .with_graceful_shutdown(shutdown)
            .await
            .map_err(|e| ViewerError::Serve(e.to_string()))
    }
}

fn headers(content_type: &'static str) -> [(header::HeaderName, &'static str); 3] {
    [
        (header::CONTENT_TYPE, content_type),
        (header::CACHE_CONTROL, "no-cache"),
        (header::X_CONTENT_TYPE_OPTIONS, "nosniff"),
    ]
}

fn not_found() -> Response {
    (
        StatusCode::NOT_FOUND,
        headers("text/plain; charset=utf-8"),
        "not found",
    )
        .into_response()
}

async fn static_asset(method: Method, uri: Uri) -> Response {
    if method != Method::GET && method != Method::HEAD {
        return (StatusCode::METHOD_NOT_ALLOWED, "only GET").into_response();
    }
    match asset(uri.path()) {
        Some(a) => (StatusCode::OK, headers(a.content_type), a.bytes).into_response(),
        None => not_found(),
    }
}

/// `/api/model/<k>.glb`: the building's part `k` (decimal, no sign or leading zeros).
async fn model(State(app): State<Arc<App>>, Path(file): Path<String>) -> Response {
    let part = file
        .strip_suffix(".glb")
        .filter(|k| !k.is_empty() && k.bytes().all(|b| b.is_ascii_digit()))
        .filter(|k| *k == "0" || !k.starts_with('0'))
        .and_then(|k| k.parse::<usize>().ok())
        .and_then(|k| app.model.get(k));
    match part {
        Some(glb) => (StatusCode::OK, headers("model/gltf-binary"), glb.clone()).into_response(),
        None => not_found(),
    }
}

async fn scene(State(app): State<Arc<App>>) -> Response {
    (
        StatusCode::OK,
        headers("application/json"),
        app.scene.clone(),
    )
        .into_response()
}

async fn element(State(app): State<Arc<App>>, Path(guid): Path<String>) -> Response {
    match app.elements.get(&guid) {
        Some(j) => (StatusCode::OK, headers("application/json"), j.clone()).into_response(),
        None => not_found(),
    }
}

/// A connected page's place in the client count, given back when it ends.
#[derive(Debug)]
struct Slot(Arc<App>);

impl Drop for Slot {
    fn drop(&mut self) {
        self.0.clients.fetch_sub(1, Ordering::SeqCst);
    }
}

/// True when the request's Origin (if any) is the server itself: pages of other sites must
/// not drive the robots through the user's browser.
fn same_origin(headers: &HeaderMap) -> bool {
    let Some(origin) = headers.get(header::ORIGIN) else {
        return true;
    };
    let (Ok(origin), Some(Ok(host))) = (
        origin.to_str(),
        headers.get(header::HOST).map(|h| h.to_str()),
    ) else {
        return false;
    };
    origin
        .strip_prefix("http://")
        .or_else(|| origin.strip_prefix("https://"))
        .is_some_and(|o| o == host)
}

async fn ws(
    State(app): State<Arc<App>>,
    headers: HeaderMap,
    upgrade: WebSocketUpgrade,
) -> Response {
    if !same_origin(&headers) {
        return (StatusCode::FORBIDDEN, "cross-origin WebSocket refused").into_response();
    }
    let max = app.config.max_clients;
    if app
        .clients
        .fetch_update(Ordering::SeqCst, Ordering::SeqCst, |n| {
            (n < max).then_some(n + 1)
        })
        .is_err()
    {
        return (
            StatusCode::SERVICE_UNAVAILABLE,
            format!("too many viewers connected (limit {max})"),
        )
            .into_response();
    }
    let slot = Slot(app.clone());
    let size = app.config.max_message_bytes;
    upgrade
        .max_message_size(size)
        .max_frame_size(size)
        .on_upgrade(move |socket| client(socket, slot))
}

/// Messages per second with a burst allowance.
#[derive(Debug)]
struct Bucket {
    tokens: f64,
    rate: f64,
    last: Instant,
}

impl Bucket {
    fn new(rate: u32) -> Bucket {
        let rate = f64::from(rate.max(1));
        Bucket {
            tokens: 2.0 * rate,
            rate,
            last: Instant::now(),
        }
    }

    fn take(&mut self) -> bool {
        let now = Instant::now();
        self.tokens =
            (self.tokens + (now - self.last).as_secs_f64() * self.rate).min(2.0 * self.rate);
        self.last = now;
        if self.tokens >= 1.0 {
            self.tokens -= 1.0;
            true
        } else {
            false
        }
    }
}

fn error_text(message: &str) -> Message {
    Message::Text(
        json!({"type": "error", "message": message})
            .to_string()
            .into(),
    )
}

fn close(code: u16, reason: &'static str) -> Message {
    Message::Close(Some(CloseFrame {
        code,
        reason: reason.into(),
    }))
}

fn command(m: ClientMessage) -> Option<Command> {
    Some(match m {
        ClientMessage::Key { robot, key, down } => Command::Key {
            robot,
            key: parse_key(&key).ok()?,
            down,
            name: key,
        },
        ClientMessage::Brush { robot } => Command::Brush { robot },
        ClientMessage::Pause { paused } => Command::Pause(paused),
        ClientMessage::Reset => Command::Reset,
        ClientMessage::Storey { index } => Command::Storey(index),
    })
}

async fn client(mut socket: WebSocket, slot: Slot) {
    let app = slot.0.clone();
    let mut states = app.live.subscribe();
    let (latest, events) = app.live.snapshot();
    if socket.send(Message::Text(events.into())).await.is_err() {
        return;
    }
    if let Some(s) = latest {
        if socket
            .send(Message::Text(s.to_string().into()))
            .await
            .is_err()
        {
            return;
        }
    }
    let mut bucket = Bucket::new(app.config.max_messages_per_second);
    let mut malformed = 0u32;
    loop {
        tokio::select! {
            incoming = socket.recv() => {
                let reply = match incoming {
                    None | Some(Ok(Message::Close(_))) => break,
                    Some(Err(_)) => {
                        // Over the size limit, or not WebSocket at all: this connection ends.
                        let _ = socket.send(close(CLOSE_TOO_BIG, "message too big or invalid")).await;
                        break;
                    }
                    Some(Ok(Message::Text(text))) => {
                        if !bucket.take() {
                            Some("too many messages: slow down".to_string())
                        } else {
                            match ClientMessage::parse(text.as_str(), app.live.robots(), app.live.robots_per_storey()).map(command) {
                                Ok(Some(c)) => {
                                    app.live.send(c);
                                    None
                                }
                                Ok(None) => None,
                                Err(e) => {
                                    malformed += 1;
                                    Some(e.to_page())
                                }
                            }
                        }
                    }
                    Some(Ok(Message::Binary(_))) => {
                        malformed += 1;
                        Some("binary messages are not accepted: send JSON text".to_string())
                    }
                    Some(Ok(_)) => None,
                };
                if malformed > app.config.max_malformed {
                    let _ = socket.send(close(CLOSE_POLICY, "too many malformed messages")).await;
                    break;
                }
                if let Some(r) = reply {
                    if socket.send(error_text(&r)).await.is_err() {
                        break;
                    }
                }
            }
            state = states.recv() => match state {
                Ok(s) => {
                    if socket.send(Message::Text(s.to_string().into())).await.is_err() {
                        break;
                    }
                }
                Err(RecvError::Lagged(_)) => continue,
                Err(RecvError::Closed) => break,
            },
        }
    }
}
