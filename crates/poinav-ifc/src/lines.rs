//! Byte offset to line number mapping, built once on demand (LF, CRLF and CR-only line ends).

/// Start offsets of every line of a buffer.
#[derive(Debug)]
pub(crate) struct LineTable {
    starts: Vec<usize>,
}

impl LineTable {
    pub(crate) fn new(bytes: &[u8]) -> LineTable {
        let mut starts = vec![0];
        for i in memchr::memchr2_iter(b'\n', b'\r', bytes) {
            // A CR directly followed by LF ends its line at the LF.
            if bytes[i] == b'\r' && bytes.get(i + 1) == Some(&b'\n') {
                continue;
            }
            starts.push(i + 1);
        }
        LineTable { starts }
    }

    /// 1-based line number of `offset`.
    pub(crate) fn line(&self, offset: usize) -> usize {
        self.starts.partition_point(|&s| s <= offset)
    }
}

/// 1-based line number of `offset`, counted directly (for one-off errors).
pub(crate) fn line_of(bytes: &[u8], offset: usize) -> usize {
    LineTable::new(&bytes[..offset.min(bytes.len())]).line(offset)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lf_crlf_and_cr_only_line_ends_count_alike() {
        for text in ["a\nb\nc", "a\r\nb\r\nc", "a\rb\rc"] {
            let t = LineTable::new(text.as_bytes());
            let c = text.find('c').unwrap();
            assert_eq!(t.line(0), 1, "{text:?}");
            assert_eq!(t.line(c), 3, "{text:?}");
            assert_eq!(line_of(text.as_bytes(), c), 3);
        }
    }
}
