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

/// The offset of the `'` that closes the string literal whose opening `'` is at `open`, or
/// `None` when it never closes within `b`.
///
/// `''` is a quote inside the string. `\S\'` (the `\S\` directive applied to an
/// apostrophe, byte 0xA7, which ISO 10303-21 allows and some exporters write) is ambiguous
/// with a string ending in `\S\`: the escape wins (as the standard and IfcOpenShell read it)
/// unless reading it so leaves the string closing where no value may end, while ending the
/// string at that apostrophe would not. A value may end before white space and `,`, `)` or
/// the end of `b`.
pub(crate) fn literal_end(b: &[u8], open: usize) -> Option<usize> {
    let content = open + 1;
    // How far the content has been split into directives and characters (see `directive_at`).
    let mut walked = content;
    // The last `\S\'` whose apostrophe could also end the string well.
    let mut fallback = None;
    let mut i = content;
    loop {
        let Some(q) = b
            .get(i..)
            .and_then(|rest| memchr::memchr(b'\'', rest))
            .map(|q| i + q)
        else {
            return fallback;
        };
        if q >= content + 3 && &b[q - 3..q] == b"\\S\\" && directive_at(b, &mut walked, q - 3) {
            if value_may_end_after(b, q) {
                fallback = Some(q);
            }
            i = q + 1;
            continue;
        }
        if b.get(q + 1) == Some(&b'\'') {
            i = q + 2;
            continue;
        }
        return match fallback {
            Some(f) if !value_may_end_after(b, q) => Some(f),
            _ => Some(q),
        };
    }
}

/// True when the backslash at `at` starts a directive, splitting the content from `*walked`
/// (which only moves forward, so a string is split once however many `\S\'` it holds).
fn directive_at(b: &[u8], walked: &mut usize, at: usize) -> bool {
    let mut w = *walked;
    while w < at {
        w += match b[w] {
            b'\\' if b.get(w + 1) == Some(&b'\\') => 2,
            b'\\' if b.get(w + 1..w + 3) == Some(b"S\\") && w + 3 < b.len() => 4,
            b'\'' => 2,
            _ => 1,
        };
    }
    *walked = w;
    w == at
}

/// True when only white space stands between `q` and a `,`, a `)` or the end of `b`.
fn value_may_end_after(b: &[u8], q: usize) -> bool {
    matches!(
        b[q + 1..].iter().find(|c| !c.is_ascii_whitespace()),
        None | Some(b',' | b')')
    )
}

/// Checks the escapes of the raw bytes between the quotes of a STEP string, ignoring whether
/// other bytes are UTF-8: the first escape that is not a defined directive, by offset.
pub fn check_escapes(raw: &[u8]) -> Result<(), StringError> {
    let mut i = 0;
    let mut page = b'A';
    while let Some(p) = memchr::memchr(b'\\', &raw[i..]) {
        let at = i + p;
        match escape(raw, at, page, true) {
            Some((Escape::Page(p), next)) => {
                page = p;
                i = next;
            }
            Some((Escape::Text(_), next)) => i = next,
            None => return Err(StringError::BadEscape(at)),
        }
    }
    Ok(())
}

/// Decodes the raw bytes between the quotes of a STEP string.
///
/// Raw UTF-8 (which many exporters write although the standard asks for escapes) is accepted.
/// Returns an error for an invalid escape or for bytes that are not UTF-8; [`decode_lossy`]
/// never fails.
pub fn decode(raw: &[u8]) -> Result<Cow<'_, str>, StringError> {
    decode_with(raw, true)
}

/// Like [`decode`], but keeps an invalid escape as literal text (a lone or trailing `\`,
/// `\X\` without two hex digits) and reads bytes that are not UTF-8 as ISO 8859-1, so nothing
/// is lost and nothing fails; `\X2\` or `\X4\` without its closing `\X0\` decodes the
/// whole code units that follow it.
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
            b'\\' => match escape(raw, i, page, strict) {
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
/// Unless `strict`, `\X2\` and `\X4\` without `\X0\` take the whole code units after them.
fn escape(raw: &[u8], i: usize, page: u8, strict: bool) -> Option<(Escape, usize)> {
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
            let (body_end, next) = match memchr::memmem::find(&rest[4..], b"\\X0\\") {
                Some(e) => (e + 4, e + 8),
                None if strict => return None,
                None => {
                    // Never closed: the whole code units of the hex digits that follow.
                    let digits = rest[4..]
                        .iter()
                        .take_while(|c| c.is_ascii_hexdigit())
                        .count();
                    if digits < width {
                        return None;
                    }
                    let end = 4 + digits / width * width;
                    (end, end)
                }
            };
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
            return Some((Escape::Text(text), i + next));
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

    /// The closing quote of the literal opening `b`, as an offset into `b`.
    fn end(b: &[u8]) -> Option<usize> {
        literal_end(b, 0)
    }

    #[test]
    fn literal_ends_with_doubled_quotes_and_the_s_directive_on_an_apostrophe() {
        assert_eq!(end(b"'it''s',1"), Some(6));
        assert_eq!(end(b"'abc"), None);
        // `\S\'` is byte 0xA7 where the string goes on (a Vectorworks header)...
        assert_eq!(end(b"'a\\S\\'\\X\\91b.ifc','x')"), Some(16));
        assert_eq!(end(b"'a\\S\\'b',1)"), Some(7));
        // ... and where the apostrophe is the last character, before the closing quote.
        assert_eq!(end(b"'a\\S\\'',1)"), Some(6));
        // Standard: the directive takes the apostrophe even before `)`, when the string then
        // closes well.
        assert_eq!(end(b"'a\\S\\')b',1)"), Some(8));
        // A string ending in `\S\` (an unescaped path): the escape reading would close the
        // string where no value may end, so the apostrophe ends it.
        assert_eq!(end(b"'C:\\S\\',$,$);\n#2=IFCWALL('x',$);"), Some(6));
        assert_eq!(end(b"'C:\\S\\'"), Some(6));
        // `\\S\\'`: an escaped backslash, then `S`, then a lone backslash before the end.
        assert_eq!(end(b"'\\\\S\\'x'"), Some(5));
    }

    #[test]
    fn real_world_quirks_decode_losslessly_and_are_errors_strictly() {
        // `\S\'` inside a string is the 0xA7 of ISO 8859-1 (IfcOpenShell reads the same).
        assert_eq!(decode(b"a\\S\\'\\X\\91b").unwrap(), "a\u{a7}\u{91}b");
        assert_eq!(decode(b"a\\S\\')b").unwrap(), "a\u{a7})b");
        // A lone backslash (Windows paths written without escaping) is kept as written.
        assert_eq!(decode(b"C:\\temp\\a b"), Err(StringError::BadEscape(2)));
        assert_eq!(decode_lossy(b"C:\\temp\\a b"), "C:\\temp\\a b");
        assert_eq!(decode_lossy(b"ab\\"), "ab\\");
        assert_eq!(decode_lossy(b"C:\\S\\"), "C:\\S\\");
        // `\X\` at the end of a string, or with one hex digit.
        assert_eq!(decode(b"ab\\X\\"), Err(StringError::BadEscape(2)));
        assert_eq!(decode_lossy(b"ab\\X\\"), "ab\\X\\");
        assert_eq!(decode_lossy(b"ab\\X\\4"), "ab\\X\\4");
        // `\X2\` without `\X0\`: the whole code units that follow.
        assert_eq!(decode(b"a\\X2\\00E400F6"), Err(StringError::BadEscape(1)));
        assert_eq!(decode_lossy(b"a\\X2\\00E400F6"), "a\u{e4}\u{f6}");
        assert_eq!(decode_lossy(b"a\\X2\\00E4 rest"), "a\u{e4} rest");
        assert_eq!(decode_lossy(b"a\\X2\\00E"), "a\\X2\\00E");
        assert_eq!(decode_lossy(b"\\X4\\0001F600"), "\u{1f600}");
        // The escape check alone, whatever the other bytes.
        assert_eq!(check_escapes(b"\\X2\\00E4\\X0\\ \xff \\S\\'"), Ok(()));
        assert_eq!(
            check_escapes(b"ok \\PB\\ \\q"),
            Err(StringError::BadEscape(8))
        );
        assert_eq!(
            check_escapes(b"a\\X2\\00E4"),
            Err(StringError::BadEscape(1))
        );
    }

    proptest! {
        #[test]
        fn literal_end_never_panics(bytes in proptest::collection::vec(
            proptest::sample::select(vec![b'\'', b'\\', b'S', b'X', b'2', b',', b')', b' ', b'a']), 0..40)) {
            let mut b = vec![b'\''];
            b.extend(bytes);
            if let Some(q) = literal_end(&b, 0) {
                prop_assert!(q > 0 && b[q] == b'\'');
            }
        }

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
