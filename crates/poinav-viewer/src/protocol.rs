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

/// Why a page's message was refused; the server sends its text back as an `error` message.
#[derive(Debug, thiserror::Error)]
pub enum ProtocolError {
    /// Not JSON, or not one of the messages (unknown type or field, wrong value type).
    #[error("malformed message")]
    Malformed(#[source] serde_json::Error),
    /// No robot with that index on the storey simulated now.
    #[error("robot {robot} does not exist (robots: 0..{})", robots.saturating_sub(1))]
    NoSuchRobot {
        /// The index asked for.
        robot: usize,
        /// How many robots there are.
        robots: usize,
    },
    /// No storey with that index.
    #[error("storey {index} does not exist (storeys: 0..{})", storeys.saturating_sub(1))]
    NoSuchStorey {
        /// The index asked for.
        index: usize,
        /// How many storeys the scene has.
        storeys: usize,
    },
    /// The storey has no robots to simulate.
    #[error("storey {index} has no robots")]
    StoreyWithoutRobots {
        /// The index asked for.
        index: usize,
    },
    /// A key name longer than any key's.
    #[error("key name too long")]
    KeyNameTooLong,
    /// Not a driving key of either scheme.
    #[error("key `{name}` is not one of ArrowUp, ArrowDown, ArrowLeft, ArrowRight, w, a, s, d")]
    UnknownKey {
        /// The name sent.
        name: String,
    },
    /// The brush sent as a key.
    #[error("the brush has its own message: {{\"type\":\"brush\",\"robot\":N}}")]
    BrushAsKey,
}

impl ProtocolError {
    /// The text sent back to the page: the error and, for a malformed message, serde's reason.
    pub fn to_page(&self) -> String {
        match self {
            ProtocolError::Malformed(e) => format!("{self}: {e}"),
            _ => self.to_string(),
        }
    }
}

impl ClientMessage {
    /// Parses and checks one text message against `robots` robots on the storey simulated now
    /// and `per_storey` robots on each storey (a storey without robots cannot be chosen).
    pub fn parse(
        text: &str,
        robots: usize,
        per_storey: &[usize],
    ) -> Result<ClientMessage, ProtocolError> {
        let m: ClientMessage = serde_json::from_str(text).map_err(ProtocolError::Malformed)?;
        match &m {
            ClientMessage::Key { robot, key, .. } => {
                check_robot(*robot, robots)?;
                parse_key(key)?;
            }
            ClientMessage::Brush { robot } => check_robot(*robot, robots)?,
            ClientMessage::Storey { index } => match per_storey.get(*index) {
                None => {
                    return Err(ProtocolError::NoSuchStorey {
                        index: *index,
                        storeys: per_storey.len(),
                    })
                }
                Some(0) => return Err(ProtocolError::StoreyWithoutRobots { index: *index }),
                Some(_) => {}
            },
            ClientMessage::Pause { .. } | ClientMessage::Reset => {}
        }
        Ok(m)
    }
}

fn check_robot(robot: usize, robots: usize) -> Result<(), ProtocolError> {
    if robot < robots {
        Ok(())
    } else {
        Err(ProtocolError::NoSuchRobot { robot, robots })
    }
}

/// A driving key by name in either scheme (`ArrowUp`, `Up`, `w`, ...); the brush has its own
/// message.
pub fn parse_key(name: &str) -> Result<Key, ProtocolError> {
    if name.len() > 16 {
        return Err(ProtocolError::KeyNameTooLong);
    }
    let key = Key::parse(KeyScheme::Arrows, name)
        .or_else(|_| Key::parse(KeyScheme::Wasd, name))
        .map_err(|_| ProtocolError::UnknownKey {
            name: name.to_string(),
        })?;
    if key == Key::Brush {
        return Err(ProtocolError::BrushAsKey);
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
        assert_eq!(parse_key("W").unwrap(), Key::Forward);
        assert_eq!(parse_key("ArrowLeft").unwrap(), Key::Left);
        assert_eq!(
            parse_key("Brush").unwrap_err().to_page(),
            r#"the brush has its own message: {"type":"brush","robot":N}"#
        );
        assert_eq!(
            parse_key("q").unwrap_err().to_page(),
            "key `q` is not one of ArrowUp, ArrowDown, ArrowLeft, ArrowRight, w, a, s, d"
        );
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
        assert_eq!(ok.unwrap(), ClientMessage::Storey { index: 2 });
        let empty = ClientMessage::parse(r#"{"type":"storey","index":1}"#, 2, &per_storey);
        assert_eq!(empty.unwrap_err().to_page(), "storey 1 has no robots");
        let missing = ClientMessage::parse(r#"{"type":"storey","index":3}"#, 2, &per_storey);
        assert_eq!(
            missing.unwrap_err().to_page(),
            "storey 3 does not exist (storeys: 0..2)"
        );
        let robot = ClientMessage::parse(r#"{"type":"brush","robot":2}"#, 2, &per_storey);
        assert_eq!(
            robot.unwrap_err().to_page(),
            "robot 2 does not exist (robots: 0..1)"
        );
        let malformed = ClientMessage::parse("not json", 2, &per_storey).unwrap_err();
        assert!(
            malformed
                .to_page()
                .starts_with("malformed message: expected ident at line 1 column 2"),
            "{}",
            malformed.to_page()
        );
    }
}
