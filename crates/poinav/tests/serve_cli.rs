//! `poinav serve` on real buildings: it listens on loopback and prints the URL, places two
//! robots in the largest space of a corpus building, serves the building's GLB and what a
//! click shows (GlobalId, class, POI roles, property sets), and refuses bad input with exit 2.

mod common;

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::process::{Child, Command, Stdio};

use serde_json::Value;

struct Server(Child);

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

fn get(addr: &str, path: &str) -> (u16, Vec<u8>) {
    let mut s = TcpStream::connect(addr).unwrap();
    write!(
        s,
        "GET {path} HTTP/1.1\r\nHost: {addr}\r\nConnection: close\r\n\r\n"
    )
    .unwrap();
    let mut buf = Vec::new();
    s.read_to_end(&mut buf).unwrap();
    let end = buf.windows(4).position(|w| w == b"\r\n\r\n").unwrap();
    let head = String::from_utf8_lossy(&buf[..end]).to_string();
    let status = head.split_whitespace().nth(1).unwrap().parse().unwrap();
    (status, buf[end + 4..].to_vec())
}

fn serve(args: &[&str]) -> (Server, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_poinav"))
        .arg("serve")
        .args(args)
        .args(["--port", "0"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut line = String::new();
    BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut line)
        .unwrap();
    let server = Server(child);
    let url = line
        .trim()
        .strip_prefix("poinav viewer: http://")
        .unwrap_or_else(|| panic!("first line {line:?}"))
        .trim_end_matches('/')
        .to_string();
    (server, url)
}

#[test]
fn serves_a_corpus_building_with_two_robots_on_loopback() {
    let file = common::shared().join("ifc/fzk-haus-ifc4.ifc");
    let (_server, addr) = serve(&[file.to_str().unwrap()]);
    assert!(addr.starts_with("127.0.0.1:"), "{addr}");
    let (status, body) = get(&addr, "/api/scene");
    assert_eq!(status, 200);
    let scene: Value = serde_json::from_slice(&body).unwrap();
    assert_eq!(scene["robots"].as_array().unwrap().len(), 2);
    assert_eq!(scene["robots"][0]["keys"], "arrows");
    assert_eq!(scene["robots"][1]["keys"], "wasd");
    assert_eq!(scene["robots"][0]["ray_hit"], "#ef4444");
    assert_eq!(scene["robots"][1]["ray_hit"], "#3b82f6");
    assert!(
        scene["zones"].as_array().unwrap().len() >= 5,
        "{}",
        scene["zones"]
    );
    assert!(!scene["doors"].as_array().unwrap().is_empty());
    let (status, glb) = get(&addr, "/api/model.glb");
    assert_eq!(status, 200);
    assert_eq!(&glb[..4], b"glTF");
    assert!(glb.len() > 100_000, "GLB {} bytes", glb.len());
    // A door: what a click shows.
    let door = scene["doors"][0]["id"].as_str().unwrap().to_string();
    let (status, body) = get(&addr, &format!("/api/element/{door}"));
    assert_eq!(status, 200);
    let info: Value = serde_json::from_slice(&body).unwrap();
    assert_eq!(info["GlobalId"], door.as_str());
    assert_eq!(info["Class"], "IfcDoor");
    assert!(info["POI"]["POI_PrimaryRoles"]
        .as_str()
        .unwrap()
        .contains("A-2"));
    assert!(info["POI"]["AccessibilityStatus"].is_string());
    assert!(
        !info["PropertySets"].as_object().unwrap().is_empty(),
        "{info}"
    );
    let (status, _) = get(&addr, "/api/element/no-such-id");
    assert_eq!(status, 404);
}

#[test]
fn bad_input_exits_2_with_the_reason() {
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("missing.ifc");
    let (code, _, err) = common::poinav(&["serve".as_ref(), missing.as_os_str()]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("missing.ifc"), "{err}");
    let bad = dir.path().join("bad.ifc");
    std::fs::write(
        &bad,
        "ISO-10303-21;\nHEADER;\nENDSEC;\nDATA;\n#1=IFCWALL('x',$,$,$,$,$,$,$;\n",
    )
    .unwrap();
    let (code, _, err) = common::poinav(&["serve".as_ref(), bad.as_os_str()]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("bad.ifc"), "{err}");
    let (code, _, err) = common::poinav(&["serve".as_ref()]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("<FILE>"), "{err}");
}
