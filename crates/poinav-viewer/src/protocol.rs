//! The messages a page sends over the WebSocket (JSON, one object per text message) and how
//! they are checked. The server's own messages (`hello`, `state`, `error`) are documented in
//! `web/viewer.js`, which reads them.

use poinav_sim::controller::{Key, KeyScheme};
use serde::Deserialize;

/// A message from a page.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(tag = "type", rename_all = "lowercase", deny_unknown_fields)]
pub enum ClientMessage {
    /// A driving key of robot `robot` (index) went down or up: `ArrowUp`.. or `w`, `a`, `s`,
    /// `d`.
    Key {
        /// Robot index.
        robot: usize,
        /// Key name (either scheme is accepted for any robot).
        key: String,
        /// Pressed or released.
        down: bool,
    },
    /// The brush button of robot `robot`.
    Brush {
        /// Robot index.
        robot: usize,
    },
    /// Pause (true) or resume (false) the simulation.
    Pause {
        /// Paused.
        paused: bool,
    },
    /// Start the simulation again from the robots' start poses.
    Reset,
    /// Simulate on another storey (index in the scene's `storeys`), with its robots.
    Storey {
        /// Storey index.
        index: usize,
    },
}

impl ClientMessage {
    /// Parses and checks one text message against `robots` robots on the storey simulated now
    /// and `per_storey` robots on each storey (a storey without robots cannot be chosen).
    pub fn parse(text: &str, robots: usize, per_storey: &[usize]) -> Result<ClientMessage, String> {
        let m: ClientMessage =
            serde_json::from_str(text).map_err(|e| format!("malformed message: {e}"))?;
        match &m {
            ClientMessage::Key { robot, key, .. } => {
                check_robot(*robot, robots)?;
                parse_key(key)?;
            }
            ClientMessage::Brush { robot } => check_robot(*robot, robots)?,
            ClientMessage::Storey { index } => match per_storey.get(*index) {
                None => {
                    return Err(format!(
                        "storey {index} does not exist (storeys: 0..{})",
                        per_storey.len().saturating_sub(1)
                    ))
                }
                Some(0) => return Err(format!("storey {index} has no robots")),
                Some(_) => {}
            },
            ClientMessage::Pause { .. } | ClientMessage::Reset => {}
        }
        Ok(m)
    }
}

fn check_robot(robot: usize, robots: usize) -> Result<(), String> {
    if robot < robots {
        Ok(())
    } else {
        Err(format!(
            "robot {robot} does not exist (robots: 0..{})",
            robots.saturating_sub(1)
        ))
    }
}

/// A driving key by name in either scheme (`ArrowUp`, `Up`, `w`, ...); the brush has its own
/// message.
pub fn parse_key(name: &str) -> Result<Key, String> {
    if name.len() > 16 {
        return Err("key name too long".into());
    }
    let key = Key::parse(KeyScheme::Arrows, name)
        .or_else(|_| Key::parse(KeyScheme::Wasd, name))
        .map_err(|_| {
            format!(
                "key `{name}` is not one of ArrowUp, ArrowDown, ArrowLeft, ArrowRight, w, a, s, d"
            )
        })?;
    if key == Key::Brush {
        return Err("the brush has its own message: {\"type\":\"brush\",\"robot\":N}".into());
    }
    Ok(key)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn accepts_both_key_schemes_for_any_robot() {
        let m = ClientMessage::parse(
            r#"{"type":"key","robot":1,"key":"ArrowUp","down":true}"#,
            2,
            &[2],
        );
        assert!(m.is_ok());
        assert_eq!(parse_key("W"), Ok(Key::Forward));
        assert_eq!(parse_key("ArrowLeft"), Ok(Key::Left));
    }

    #[test]
    fn refuses_unknown_robots_keys_fields_and_types() {
        for bad in [
            r#"{"type":"key","robot":2,"key":"w","down":true}"#,
            r#"{"type":"key","robot":0,"key":"q","down":true}"#,
            r#"{"type":"key","robot":0,"key":"Brush","down":true}"#,
            r#"{"type":"key","robot":0,"key":"w","down":true,"extra":1}"#,
            r#"{"type":"teleport","robot":0}"#,
            r#"{"type":"key","robot":-1,"key":"w","down":true}"#,
            r#"[1,2,3]"#,
            r#"{"type":"storey","index":1}"#,
            r#"{"type":"storey"}"#,
            "not json",
            "",
        ] {
            assert!(ClientMessage::parse(bad, 2, &[2]).is_err(), "{bad}");
        }
    }

    #[test]
    fn a_storey_switch_needs_a_storey_with_robots() {
        let per_storey = [2, 0, 3];
        let ok = ClientMessage::parse(r#"{"type":"storey","index":2}"#, 2, &per_storey);
        assert_eq!(ok, Ok(ClientMessage::Storey { index: 2 }));
        let empty = ClientMessage::parse(r#"{"type":"storey","index":1}"#, 2, &per_storey);
        assert_eq!(empty, Err("storey 1 has no robots".to_string()));
        let missing = ClientMessage::parse(r#"{"type":"storey","index":3}"#, 2, &per_storey);
        assert_eq!(
            missing,
            Err("storey 3 does not exist (storeys: 0..2)".to_string())
        );
    }
}
