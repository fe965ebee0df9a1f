//! The viewer server over real sockets: assets only at their exact paths (no traversal), the
//! loopback default, WebSocket driving, and limits (size, malformed, rate, clients, origin)
//! that end or refuse one connection while the simulation and the other pages go on.

use std::collections::BTreeMap;
use std::net::SocketAddr;
use std::time::{Duration, Instant};

use futures_util::{SinkExt, StreamExt};
use glam::DVec2;
use poinav_nav::polygon::rect;
use poinav_nav::{Floor, FloorObstacle, FloorZone, ObstacleKind};
use poinav_roles::{RobotProfile, Role};
use poinav_sim::SimOptions;
use poinav_viewer::{ModelChunk, ServerConfig, ViewStorey, Viewer};
use serde_json::Value;
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::TcpStream;
use tokio_tungstenite::tungstenite::client::IntoClientRequest;
use tokio_tungstenite::tungstenite::protocol::frame::coding::CloseCode;
use tokio_tungstenite::tungstenite::{Error as WsError, Message};
use tokio_tungstenite::{connect_async, MaybeTlsStream, WebSocketStream};

type Ws = WebSocketStream<MaybeTlsStream<TcpStream>>;

/// A 10 x 6 m room inside four 0.2 m walls.
fn room() -> Floor {
    let wall = |id: &str, ring| FloorObstacle {
        id: id.into(),
        class: "IfcWall".into(),
        kind: ObstacleKind::Structure,
        rings: vec![ring],
        roles: vec![Role::Avoidance, Role::PathGuidance],
    };
    Floor {
        name: "Test floor".into(),
        elevation_m: 0.0,
        obstacles: vec![
            wall("south", rect(-0.2, -0.2, 10.2, 0.0)),
            wall("north", rect(-0.2, 6.0, 10.2, 6.2)),
            wall("west", rect(-0.2, 0.0, 0.0, 6.0)),
            wall("east", rect(10.0, 0.0, 10.2, 6.0)),
        ],
        zones: vec![FloorZone {
            id: "room".into(),
            name: Some("Room".into()),
            long_name: None,
            ring: rect(0.0, 0.0, 10.0, 6.0),
            roles: vec![Role::Destination],
            coordination: None,
        }],
        ..Floor::default()
    }
}

async fn start(config: ServerConfig) -> (SocketAddr, tokio::sync::oneshot::Sender<()>) {
    let floor = room();
    let robots = poinav_viewer::default_robots(&floor, &RobotProfile::paper()).unwrap();
    serve(config, vec![ViewStorey::new(floor, robots)]).await
}

/// The test room on the ground floor and, 3 m above, a 6 x 4 m room whose robots start
/// elsewhere; a third storey without robots.
async fn start_two_storeys() -> (SocketAddr, tokio::sync::oneshot::Sender<()>) {
    let ground = room();
    let mut upper = room();
    upper.name = "Upper floor".into();
    upper.elevation_m = 3.0;
    for o in &mut upper.obstacles {
        for p in o.rings.iter_mut().flatten() {
            *p = DVec2::new(p.x * 0.6, p.y * 4.0 / 6.0);
        }
    }
    upper.zones[0].ring = rect(0.0, 0.0, 6.0, 4.0);
    let profile = RobotProfile::paper();
    let a = poinav_viewer::default_robots(&ground, &profile).unwrap();
    let b = poinav_viewer::default_robots(&upper, &profile).unwrap();
    let roof = Floor {
        name: "Roof".into(),
        elevation_m: 6.0,
        ..Floor::default()
    };
    serve(
        ServerConfig::default(),
        vec![
            ViewStorey::new(ground, a),
            ViewStorey::new(upper, b),
            ViewStorey::unplaced(roof, "it has no spaces (IfcSpace)".into()),
        ],
    )
    .await
}

async fn serve(
    config: ServerConfig,
    storeys: Vec<ViewStorey>,
) -> (SocketAddr, tokio::sync::oneshot::Sender<()>) {
    let viewer = Viewer {
        title: "test".into(),
        model: vec![
            ModelChunk {
                storey: Some(0),
                name: "ground".into(),
                elevation_m: 0.0,
                elements: 1,
                glb: b"glTF-ground".to_vec(),
            },
            ModelChunk {
                storey: None,
                name: "No storey".into(),
                elevation_m: 0.0,
                elements: 2,
                glb: b"glTF-loose".to_vec(),
            },
        ],
        elements: BTreeMap::new(),
        storeys,
        current: 0,
        options: SimOptions::default(),
        source: "test".into(),
    };
    let bound = poinav_viewer::bind(
        ServerConfig {
            addr: "127.0.0.1:0".parse().unwrap(),
            ..config
        },
        viewer,
    )
    .await
    .unwrap();
    let addr = bound.local_addr();
    let (tx, rx) = tokio::sync::oneshot::channel::<()>();
    tokio::spawn(bound.run_until(async {
        let _ = rx.await;
    }));
    (addr, tx)
}

/// One raw HTTP/1.1 request (the path exactly as given, not normalised by a client library):
/// status code and body.
async fn raw_get(addr: SocketAddr, method: &str, path: &str) -> (u16, String) {
    let mut s = TcpStream::connect(addr).await.unwrap();
    let req = format!("{method} {path} HTTP/1.1\r\nHost: {addr}\r\nConnection: close\r\n\r\n");
    s.write_all(req.as_bytes()).await.unwrap();
    let mut buf = Vec::new();
    s.read_to_end(&mut buf).await.unwrap();
    let text = String::from_utf8_lossy(&buf).to_string();
    let status = text
        .split_whitespace()
        .nth(1)
        .and_then(|c| c.parse().ok())
        .unwrap_or(0);
    let body = text.split("\r\n\r\n").nth(1).unwrap_or("").to_string();
    (status, body)
}

async fn ws(addr: SocketAddr) -> Ws {
    connect_async(format!("ws://{addr}/ws")).await.unwrap().0
}

/// The next message of type `kind` (skipping others), within 10 s.
async fn next_of(ws: &mut Ws, kind: &str) -> Value {
    let deadline = Instant::now() + Duration::from_secs(10);
    loop {
        let left = deadline.saturating_duration_since(Instant::now());
        let m = tokio::time::timeout(left, ws.next())
            .await
            .unwrap_or_else(|_| panic!("no `{kind}` message within 10 s"))
            .expect("connection ended")
            .expect("connection failed");
        if let Message::Text(t) = m {
            let v: Value = serde_json::from_str(t.as_str()).unwrap();
            if v["type"] == kind {
                return v;
            }
        }
    }
}

/// The newest state: reads until nothing is waiting (states come every 16.7 ms; queued ones at once).
async fn latest_state(ws: &mut Ws) -> Value {
    let mut last = next_of(ws, "state").await;
    while let Ok(Some(Ok(m))) = tokio::time::timeout(Duration::from_millis(4), ws.next()).await {
        if let Message::Text(t) = m {
            let v: Value = serde_json::from_str(t.as_str()).unwrap();
            if v["type"] == "state" {
                last = v;
            }
        }
    }
    last
}

/// Waits for the connection to end; the close code, if the server sent one.
async fn closed(ws: &mut Ws) -> Option<CloseCode> {
    let deadline = Instant::now() + Duration::from_secs(10);
    loop {
        let left = deadline.saturating_duration_since(Instant::now());
        match tokio::time::timeout(left, ws.next())
            .await
            .expect("not closed within 10 s")
        {
            Some(Ok(Message::Close(frame))) => return frame.map(|f| f.code),
            Some(Ok(_)) => continue,
            Some(Err(_)) | None => return None,
        }
    }
}

fn x_of(state: &Value, robot: usize) -> f64 {
    state["robots"][robot]["x"].as_f64().unwrap()
}

#[test]
fn default_bind_address_is_loopback() {
    let c = ServerConfig::default();
    assert!(c.addr.ip().is_loopback(), "{}", c.addr);
    assert_eq!(c.addr.to_string(), "127.0.0.1:8080");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn serves_only_its_assets_and_refuses_paths_outside_them() {
    let (addr, _stop) = start(ServerConfig::default()).await;
    let (status, body) = raw_get(addr, "GET", "/").await;
    assert_eq!(status, 200);
    assert!(body.contains("<title>poinav viewer</title>"));
    let (status, body) = raw_get(addr, "GET", "/vendor/three/three.module.js").await;
    assert_eq!(status, 200);
    assert!(body.contains("three.core.js"));
    let (status, body) = raw_get(addr, "GET", "/api/model/0.glb").await;
    assert_eq!((status, body.as_str()), (200, "glTF-ground"));
    let (status, body) = raw_get(addr, "GET", "/api/model/1.glb").await;
    assert_eq!((status, body.as_str()), (200, "glTF-loose"));
    for part in [
        "2.glb",
        "01.glb",
        "+1.glb",
        "1",
        ".glb",
        "1.glb.glb",
        "-0.glb",
    ] {
        let (status, _) = raw_get(addr, "GET", &format!("/api/model/{part}")).await;
        assert_eq!(status, 404, "/api/model/{part}");
    }
    for path in [
        "/../Cargo.toml",
        "/../../../../../../etc/passwd",
        "/vendor/../../Cargo.toml",
        "/vendor/three/../../../src/lib.rs",
        "/%2e%2e/%2e%2e/Cargo.toml",
        "/vendor/three/..%2f..%2f..%2fCargo.toml",
        "/vendor%2fthree%2f..%2f..%2fviewer.js",
        "/api/element/..%2f..%2fetc%2fpasswd",
        "/api/element/../../etc/passwd",
        "//etc/passwd",
        "/viewer.js/",
        "/web/index.html",
        "/src/lib.rs",
    ] {
        let (status, body) = raw_get(addr, "GET", path).await;
        assert!(
            status == 404 || status == 400,
            "{path}: HTTP {status}, {} bytes",
            body.len()
        );
        assert!(
            !body.contains("root:") && !body.contains("[package]") && !body.contains("//!"),
            "{path} leaked a file"
        );
    }
    let (status, _) = raw_get(addr, "POST", "/").await;
    assert_eq!(status, 405);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_key_held_over_the_websocket_drives_its_robot_only() {
    let (addr, _stop) = start(ServerConfig::default()).await;
    let mut page = ws(addr).await;
    let before = latest_state(&mut page).await;
    page.send(Message::text(
        r#"{"type":"key","robot":0,"key":"ArrowUp","down":true}"#,
    ))
    .await
    .unwrap();
    // Held until it has moved (a loaded machine may run the simulation slower than real time).
    let deadline = Instant::now() + Duration::from_secs(10);
    let moved = |a: &Value, b: &Value| {
        let d = |k: &str| a["robots"][0][k].as_f64().unwrap() - b["robots"][0][k].as_f64().unwrap();
        d("x").hypot(d("y"))
    };
    let mut after = latest_state(&mut page).await;
    while moved(&after, &before) <= 0.3 && Instant::now() < deadline {
        tokio::time::sleep(Duration::from_millis(50)).await;
        after = latest_state(&mut page).await;
    }
    page.send(Message::text(
        r#"{"type":"key","robot":0,"key":"ArrowUp","down":false}"#,
    ))
    .await
    .unwrap();
    let moved = moved(&after, &before);
    assert!(moved > 0.3, "Robot1 moved {moved} m");
    assert_eq!(x_of(&after, 1), x_of(&before, 1), "Robot2 must not move");
    assert!(after["step"].as_u64() > before["step"].as_u64());
    assert_eq!(after["robots"][0]["mode"], "keys");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn an_oversized_message_ends_that_connection_only() {
    let (addr, _stop) = start(ServerConfig::default()).await;
    let mut bad = ws(addr).await;
    let mut good = ws(addr).await;
    next_of(&mut bad, "state").await;
    let big = format!(r#"{{"type":"reset","pad":"{}"}}"#, "x".repeat(64 * 1024));
    // The server may close before the whole message is written.
    let _ = bad.send(Message::text(big)).await;
    let code = closed(&mut bad).await;
    assert!(
        code.is_none() || code == Some(CloseCode::Size),
        "closed with {code:?}"
    );
    let s1 = latest_state(&mut good).await;
    let deadline = Instant::now() + Duration::from_secs(10);
    let mut s2 = latest_state(&mut good).await;
    while s2["step"].as_u64().unwrap() <= s1["step"].as_u64().unwrap() + 5
        && Instant::now() < deadline
    {
        tokio::time::sleep(Duration::from_millis(50)).await;
        s2 = latest_state(&mut good).await;
    }
    assert!(
        s2["step"].as_u64().unwrap() > s1["step"].as_u64().unwrap() + 5,
        "the simulation must go on: {} -> {}",
        s1["step"],
        s2["step"]
    );
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn malformed_messages_get_errors_then_the_connection_is_closed() {
    let config = ServerConfig {
        max_malformed: 5,
        ..ServerConfig::default()
    };
    let (addr, _stop) = start(config).await;
    let mut page = ws(addr).await;
    for (bad, says) in [
        (Message::text("not json"), "malformed message"),
        (
            Message::text(r#"{"type":"key","robot":7,"key":"w","down":true}"#),
            "robot 7 does not exist",
        ),
        (
            Message::text(r#"{"type":"key","robot":0,"key":"F5","down":true}"#),
            "key `F5`",
        ),
        (Message::binary(vec![0u8, 1, 2]), "binary messages"),
    ] {
        page.send(bad).await.unwrap();
        let e = next_of(&mut page, "error").await;
        assert!(
            e["message"].as_str().unwrap().contains(says),
            "{e} should say {says}"
        );
    }
    // Still connected: a valid message works.
    page.send(Message::text(r#"{"type":"brush","robot":1}"#))
        .await
        .unwrap();
    let deadline = Instant::now() + Duration::from_secs(5);
    loop {
        let s = next_of(&mut page, "state").await;
        if s["robots"][1]["brush"]["on"] == true {
            break;
        }
        assert!(Instant::now() < deadline, "brush never turned on");
    }
    for _ in 0..3 {
        let _ = page.send(Message::text("{}")).await;
    }
    assert_eq!(closed(&mut page).await, Some(CloseCode::Policy));
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn message_floods_are_refused_without_disconnecting() {
    let config = ServerConfig {
        max_messages_per_second: 10,
        ..ServerConfig::default()
    };
    let (addr, _stop) = start(config).await;
    let mut page = ws(addr).await;
    for _ in 0..60 {
        page.send(Message::text(r#"{"type":"pause","paused":false}"#))
            .await
            .unwrap();
    }
    let e = next_of(&mut page, "error").await;
    assert!(e["message"].as_str().unwrap().contains("too many messages"));
    let s = next_of(&mut page, "state").await;
    assert_eq!(s["paused"], false);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn more_pages_than_the_limit_are_refused_and_slots_come_back() {
    let config = ServerConfig {
        max_clients: 2,
        ..ServerConfig::default()
    };
    let (addr, _stop) = start(config).await;
    let mut a = ws(addr).await;
    let mut b = ws(addr).await;
    next_of(&mut a, "state").await;
    next_of(&mut b, "state").await;
    match connect_async(format!("ws://{addr}/ws")).await {
        Err(WsError::Http(r)) => assert_eq!(r.status().as_u16(), 503),
        other => panic!("a third page must be refused, got {:?}", other.map(|_| ())),
    }
    // The two connected pages keep receiving.
    let s1 = next_of(&mut a, "state").await;
    let s2 = next_of(&mut a, "state").await;
    assert!(s2["step"].as_u64() > s1["step"].as_u64());
    a.close(None).await.unwrap();
    drop(a);
    let deadline = Instant::now() + Duration::from_secs(5);
    let mut c = loop {
        match connect_async(format!("ws://{addr}/ws")).await {
            Ok((c, _)) => break c,
            Err(_) if Instant::now() < deadline => {
                tokio::time::sleep(Duration::from_millis(50)).await
            }
            Err(e) => panic!("the freed slot never came back: {e}"),
        }
    };
    next_of(&mut c, "state").await;
    next_of(&mut b, "state").await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn websockets_from_other_sites_are_refused() {
    let (addr, _stop) = start(ServerConfig::default()).await;
    let mut req = format!("ws://{addr}/ws").into_client_request().unwrap();
    req.headers_mut()
        .insert("Origin", "http://evil.example".parse().unwrap());
    match connect_async(req).await {
        Err(WsError::Http(r)) => assert_eq!(r.status().as_u16(), 403),
        other => panic!("must be refused, got {:?}", other.map(|_| ())),
    }
    let mut req = format!("ws://{addr}/ws").into_client_request().unwrap();
    req.headers_mut()
        .insert("Origin", format!("http://{addr}").parse().unwrap());
    let (mut same, _) = connect_async(req).await.unwrap();
    next_of(&mut same, "state").await;
}

#[test]
fn default_robots_start_apart_in_the_largest_space_facing_open_space() {
    let floor = room();
    let robots = poinav_viewer::default_robots(&floor, &RobotProfile::paper()).unwrap();
    assert_eq!(robots.len(), 2);
    assert_eq!(
        (robots[0].name.as_str(), robots[1].name.as_str()),
        ("Robot1", "Robot2")
    );
    let (a, b) = (robots[0].start, robots[1].start);
    assert!(a.distance(b) >= 2.5, "{a} {b}");
    // Most room in a 10 x 6 room: on the long centre line, 3 m from the long walls.
    assert!(
        (a.y - 3.0).abs() < 0.051 && (b.y - 3.0).abs() < 0.051,
        "{a} {b}"
    );
    // Neither faces the other (their first move must not hit it), and each has at least 2 m of
    // room ahead inside the 10 x 6 m room.
    for (r, other) in [(&robots[0], b), (&robots[1], a)] {
        let towards = (other - r.start).to_angle().to_degrees();
        let off = (r.heading_deg - towards + 540.0).rem_euclid(360.0) - 180.0;
        assert!(off.abs() >= 60.0, "{} faces the other robot: {off}", r.name);
        let d = DVec2::from_angle(r.heading_deg.to_radians());
        let room_ahead = [
            (10.0 - r.start.x) / d.x,
            -r.start.x / d.x,
            (6.0 - r.start.y) / d.y,
            -r.start.y / d.y,
        ]
        .into_iter()
        .filter(|t| t.is_finite() && *t > 0.0)
        .fold(f64::MAX, f64::min);
        assert!(room_ahead >= 2.0, "{}: {room_ahead} m ahead", r.name);
    }
    let empty = Floor::default();
    let e = poinav_viewer::default_robots(&empty, &RobotProfile::paper()).unwrap_err();
    assert!(e.to_string().contains("no spaces"), "{e}");
}

#[tokio::test]
async fn a_page_moves_the_robots_to_another_storey() {
    let (addr, _stop) = start_two_storeys().await;
    let (status, body) = raw_get(addr, "GET", "/api/scene").await;
    assert_eq!(status, 200);
    let scene: Value = serde_json::from_str(&body).unwrap();
    assert_eq!(scene["current"], 0);
    assert_eq!(scene["storey"], "Test floor");
    let storeys = scene["storeys"].as_array().unwrap();
    assert_eq!(storeys.len(), 3);
    assert_eq!(storeys[1]["elevation_m"], 3.0);
    assert_eq!(storeys[1]["structure"].as_array().unwrap().len(), 4);
    assert_eq!(storeys[2]["robots"].as_array().unwrap().len(), 0);
    assert_eq!(storeys[2]["unplaced"], "it has no spaces (IfcSpace)");
    // The building's parts: where each is served, its storey and size.
    assert_eq!(
        scene["model"],
        serde_json::json!([
            {"url": "/api/model/0.glb", "storey": 0, "name": "ground", "elevation_m": 0.0, "elements": 1, "bytes": 11},
            {"url": "/api/model/1.glb", "storey": null, "name": "No storey", "elevation_m": 0.0, "elements": 2, "bytes": 10},
        ])
    );
    let start = &storeys[1]["robots"][0]["start"];
    let mut page = ws(addr).await;
    assert_eq!(latest_state(&mut page).await["storey"], 0);
    // A storey without robots is refused, and the simulation stays where it is.
    page.send(Message::Text(r#"{"type":"storey","index":2}"#.into()))
        .await
        .unwrap();
    let e = next_of(&mut page, "error").await;
    assert_eq!(e["message"], "storey 2 has no robots");
    page.send(Message::Text(r#"{"type":"storey","index":1}"#.into()))
        .await
        .unwrap();
    let deadline = Instant::now() + Duration::from_secs(10);
    let state = loop {
        let s = latest_state(&mut page).await;
        if s["storey"] == 1 {
            break s;
        }
        assert!(Instant::now() < deadline, "the storey never changed");
    };
    // The robots stand at the upper storey's start poses (inside its 6 x 4 m room).
    let x = state["robots"][0]["x"].as_f64().unwrap();
    let y = state["robots"][0]["y"].as_f64().unwrap();
    assert!(
        (x - start[0].as_f64().unwrap()).abs() < 0.05,
        "{x} vs {start}"
    );
    assert!(
        (y - start[1].as_f64().unwrap()).abs() < 0.05,
        "{y} vs {start}"
    );
    assert!(x < 6.0 && y < 4.0, "{x} {y}");
}
