//! XML escaping, one function for element text and one for attribute values; both also serve
//! HTML and SVG. Characters XML 1.0 cannot carry at all (C0 controls but tab and line breaks,
//! U+FFFE, U+FFFF) become U+FFFD, so the output always parses.

use std::fmt::Write;

/// Escapes `s` for XML element content: `&`, `<`, `>` as entities, a carriage return as
/// `&#13;` (a parser would turn a raw one into a line feed), illegal characters as U+FFFD.
pub fn text(s: &str) -> String {
    escape(s, false)
}

/// Escapes `s` for a double-quoted attribute value (every poinav writer quotes attributes with
/// `"`), also safe as element text: [`text`]'s escapes plus `"`, and tab and line breaks as
/// character references (a parser would normalise raw ones to spaces). An apostrophe stays as
/// it is, as all of poinav's writers wrote it but the IDS writer.
pub fn attr(s: &str) -> String {
    escape(s, true)
}

fn escape(s: &str, attr: bool) -> String {
    let mut out = String::with_capacity(s.len());
    for ch in s.chars() {
        match ch {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' if attr => out.push_str("&quot;"),
            '\t' | '\n' | '\r' if attr => {
                let _ = write!(out, "&#{};", ch as u32);
            }
            '\r' => out.push_str("&#13;"),
            '\t' | '\n' => out.push(ch),
            c if (c as u32) < 0x20 || c == '\u{FFFE}' || c == '\u{FFFF}' => out.push('\u{FFFD}'),
            c => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_escapes_markup_and_keeps_quotes_and_line_feeds() {
        assert_eq!(text("a&b<c>\"d'"), "a&amp;b&lt;c&gt;\"d'");
        assert_eq!(text("x\ty\nz\r"), "x\ty\nz&#13;");
        assert_eq!(text("\u{1}\u{FFFE}\u{FFFF}é"), "\u{FFFD}\u{FFFD}\u{FFFD}é");
        assert_eq!(text("plain 😀"), "plain 😀");
    }

    #[test]
    fn attr_escapes_quotes_and_whitespace_as_references() {
        assert_eq!(attr("a&b<c>\"d'"), "a&amp;b&lt;c&gt;&quot;d'");
        assert_eq!(attr("x\ty\nz\r"), "x&#9;y&#10;z&#13;");
        assert_eq!(attr("R&D <1>\u{1}"), "R&amp;D &lt;1&gt;\u{FFFD}");
        assert_eq!(attr(""), "");
    }
}
