//! STEP string literals (ISO 10303-21 §6.4.3): decoding `''`, `\\`, `\S\`, `\P?\`, `\X\`,
//! `\X2\…\X0\` and `\X4\…\X0\`, and encoding Rust strings back into that form.

use std::borrow::Cow;

/// How decoding a string literal went wrong.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum StringError {
    /// A `\` escape that is not one of the defined directives.
    #[error("invalid escape sequence at byte {0} of the string")]
    BadEscape(usize),
    /// Bytes outside printable ASCII that are not valid UTF-8.
    #[error("bytes that are not UTF-8 at byte {0} of the string")]
    NonUtf8(usize),
}

/// Decodes the raw bytes between the quotes of a STEP string.
///
/// Raw UTF-8 (which many exporters write although the standard asks for escapes) is accepted.
/// Returns an error for an invalid escape or for bytes that are not UTF-8; [`decode_lossy`]
/// never fails.
pub fn decode(raw: &[u8]) -> Result<Cow<'_, str>, StringError> {
    decode_with(raw, true)
}

/// Like [`decode`], but keeps an invalid escape as literal text and reads bytes that are
/// not UTF-8 as ISO 8859-1, so nothing is lost and nothing fails.
pub fn decode_lossy(raw: &[u8]) -> Cow<'_, str> {
    decode_with(raw, false).unwrap_or_else(|_| Cow::Owned(String::new()))
}

fn decode_with(raw: &[u8], strict: bool) -> Result<Cow<'_, str>, StringError> {
    if !raw.iter().any(|&b| b == b'\\' || b == b'\'' || b >= 0x80) {
        // Plain printable ASCII: the common case, no allocation.
        return Ok(Cow::Borrowed(
            std::str::from_utf8(raw).expect("ASCII is UTF-8"),
        ));
    }
    let mut out = String::with_capacity(raw.len());
    let mut page: u8 = b'A';
    let mut i = 0;
    while i < raw.len() {
        let b = raw[i];
        match b {
            b'\'' => {
                // `''` stands for one quote; a lone quote cannot occur inside a scanned literal.
                out.push('\'');
                i += if raw.get(i + 1) == Some(&b'\'') { 2 } else { 1 };
            }
            b'\\' => match escape(raw, i, page) {
                Some((Escape::Text(s), next)) => {
                    out.push_str(&s);
                    i = next;
                }
                Some((Escape::Page(p), next)) => {
                    page = p;
                    i = next;
                }
                None if strict => return Err(StringError::BadEscape(i)),
                None => {
                    out.push('\\');
                    i += 1;
                }
            },
            0x80.. => {
                let end = raw[i..]
                    .iter()
                    .position(|&c| c < 0x80)
                    .map_or(raw.len(), |p| i + p);
                match std::str::from_utf8(&raw[i..end]) {
                    Ok(s) => out.push_str(s),
                    Err(_) if strict => return Err(StringError::NonUtf8(i)),
                    Err(_) => out.extend(raw[i..end].iter().map(|&c| char::from(c))),
                }
                i = end;
            }
            _ => {
                out.push(char::from(b));
                i += 1;
            }
        }
    }
    Ok(Cow::Owned(out))
}

enum Escape {
    Text(String),
    Page(u8),
}

fn hex(bytes: &[u8]) -> Option<u32> {
    if bytes.is_empty() || !bytes.iter().all(u8::is_ascii_hexdigit) {
        return None;
    }
    u32::from_str_radix(std::str::from_utf8(bytes).ok()?, 16).ok()
}

/// Decodes the escape starting at `raw[i] == b'\\'`; returns the text and the next index.
fn escape(raw: &[u8], i: usize, page: u8) -> Option<(Escape, usize)> {
    let rest = &raw[i..];
    if rest.starts_with(b"\\\\") {
        return Some((Escape::Text("\\".into()), i + 2));
    }
    if rest.len() >= 4 && rest.starts_with(b"\\S\\") {
        let c = rest[3];
        return Some((Escape::Text(high_half(page, c.wrapping_add(0x80))), i + 4));
    }
    if rest.len() >= 4
        && rest.starts_with(b"\\P")
        && rest[3] == b'\\'
        && rest[2].is_ascii_uppercase()
    {
        return Some((Escape::Page(rest[2]), i + 4));
    }
    if rest.starts_with(b"\\X\\") && rest.len() >= 5 {
        let v = hex(&rest[3..5])?;
        return Some((Escape::Text(char::from(v as u8).to_string()), i + 5));
    }
    for (tag, width) in [(&b"\\X2\\"[..], 4usize), (&b"\\X4\\"[..], 8usize)] {
        if rest.starts_with(tag) {
            let body_end = memchr::memmem::find(&rest[4..], b"\\X0\\")? + 4;
            let body = &rest[4..body_end];
            if body.len() % width != 0 {
                return None;
            }
            let units: Option<Vec<u32>> = body.chunks(width).map(hex).collect();
            let units = units?;
            let text = if width == 4 {
                let u16s: Vec<u16> = units.iter().map(|&u| u as u16).collect();
                String::from_utf16(&u16s).ok()?
            } else {
                units
                    .iter()
                    .map(|&u| char::from_u32(u))
                    .collect::<Option<String>>()?
            };
            return Some((Escape::Text(text), i + body_end + 4));
        }
    }
    None
}

/// A byte of the upper half of ISO 8859-`page` as text.
fn high_half(page: u8, byte: u8) -> String {
    let encoding = match page {
        b'B' => encoding_rs::ISO_8859_2,
        b'C' => encoding_rs::ISO_8859_3,
        b'D' => encoding_rs::ISO_8859_4,
        b'E' => encoding_rs::ISO_8859_5,
        b'F' => encoding_rs::ISO_8859_6,
        b'G' => encoding_rs::ISO_8859_7,
        b'H' => encoding_rs::ISO_8859_8,
        b'I' => encoding_rs::WINDOWS_1254,
        // ISO 8859-1 maps byte N to U+00N directly.
        _ => return char::from(byte).to_string(),
    };
    encoding.decode_without_bom_handling(&[byte]).0.into_owned()
}

/// Encodes text as the inside of a STEP string literal: printable ASCII as is, `'` and `\`
/// doubled, everything else as `\X2\…\X0\` (or `\X4\…\X0\` beyond the BMP).
pub fn encode(text: &str) -> String {
    let mut out = String::with_capacity(text.len() + 2);
    let mut chars = text.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '\'' => out.push_str("''"),
            '\\' => out.push_str("\\\\"),
            ' '..='~' => out.push(c),
            _ => {
                let astral = (c as u32) > 0xFFFF;
                out.push_str(if astral { "\\X4\\" } else { "\\X2\\" });
                let mut c = c;
                loop {
                    if astral {
                        out.push_str(&format!("{:08X}", c as u32));
                    } else {
                        out.push_str(&format!("{:04X}", c as u32));
                    }
                    match chars.peek() {
                        Some(&n) if !matches!(n, ' '..='~') && ((n as u32) > 0xFFFF) == astral => {
                            c = n;
                            chars.next();
                        }
                        _ => break,
                    }
                }
                out.push_str("\\X0\\");
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn decodes_every_directive() {
        assert_eq!(decode(b"it''s").unwrap(), "it's");
        assert_eq!(decode(b"a\\\\b").unwrap(), "a\\b");
        assert_eq!(decode(b"Gr\\S\\|n").unwrap(), "Grün");
        assert_eq!(decode(b"\\X\\E4").unwrap(), "ä");
        assert_eq!(decode(b"\\X2\\5ECA4E0B\\X0\\").unwrap(), "廊下");
        assert_eq!(decode(b"\\X2\\D83DDE00\\X0\\").unwrap(), "😀");
        assert_eq!(decode(b"\\X4\\0001F600\\X0\\").unwrap(), "😀");
        assert_eq!(decode(b"\\PB\\\\S\\1").unwrap(), "ą", "ISO 8859-2 page");
        assert_eq!(decode("raw ü".as_bytes()).unwrap(), "raw ü");
    }

    #[test]
    fn bad_input_is_an_error_strictly_and_kept_lossily() {
        assert_eq!(decode(b"\\Q\\"), Err(StringError::BadEscape(0)));
        assert_eq!(decode(b"\\X2\\12\\X0\\"), Err(StringError::BadEscape(0)));
        assert_eq!(decode(b"a\xff"), Err(StringError::NonUtf8(1)));
        assert_eq!(decode_lossy(b"a\xff"), "a\u{ff}");
        assert_eq!(decode_lossy(b"\\Q\\"), "\\Q\\");
    }

    proptest! {
        #[test]
        fn encode_then_decode_round_trips(s in "\\PC*") {
            let enc = encode(&s);
            prop_assert!(enc.bytes().all(|b| (b' '..=b'~').contains(&b)));
            prop_assert_eq!(decode(enc.as_bytes()).unwrap(), s);
        }

        #[test]
        fn decoding_arbitrary_bytes_never_panics(bytes in proptest::collection::vec(any::<u8>(), 0..64)) {
            let _ = decode(&bytes);
            let _ = decode_lossy(&bytes);
        }
    }
}
