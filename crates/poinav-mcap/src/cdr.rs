//! A little-endian CDR writer (plain CDR / XCDR1, what ROS 2's rmw implementations put on the
//! wire and rosbag2 records): the 4-byte encapsulation header `00 01 00 00` (CDR_LE, no
//! options), then each primitive aligned to its own size (8 at most) counted from the end of
//! that header; strings as a `u32` length that includes the NUL, the bytes and the NUL;
//! sequences as a `u32` element count then the elements; fixed arrays as the elements alone.

/// The encapsulation header of little-endian plain CDR.
pub const CDR_LE: [u8; 4] = [0x00, 0x01, 0x00, 0x00];

/// Writes one serialized message.
#[derive(Debug, Clone)]
pub struct CdrWriter {
    buf: Vec<u8>,
}

impl Default for CdrWriter {
    fn default() -> Self {
        CdrWriter::new()
    }
}

impl CdrWriter {
    /// An empty message (the encapsulation header only).
    pub fn new() -> CdrWriter {
        let mut buf = Vec::with_capacity(256);
        buf.extend_from_slice(&CDR_LE);
        CdrWriter { buf }
    }

    /// Pads with zeros so the next byte's offset (after the header) is a multiple of `n`.
    fn align(&mut self, n: usize) {
        let pos = self.buf.len() - CDR_LE.len();
        let pad = (n - pos % n) % n;
        self.buf.resize(self.buf.len() + pad, 0);
    }

    /// A `uint8` (or `byte`, `char`).
    pub fn u8(&mut self, v: u8) -> &mut Self {
        self.buf.push(v);
        self
    }

    /// An `int8`.
    pub fn i8(&mut self, v: i8) -> &mut Self {
        self.u8(v as u8)
    }

    /// A `bool` (one byte, 0 or 1).
    pub fn bool(&mut self, v: bool) -> &mut Self {
        self.u8(u8::from(v))
    }

    /// A `uint32`.
    pub fn u32(&mut self, v: u32) -> &mut Self {
        self.align(4);
        self.buf.extend_from_slice(&v.to_le_bytes());
        self
    }

    /// An `int32`.
    pub fn i32(&mut self, v: i32) -> &mut Self {
        self.align(4);
        self.buf.extend_from_slice(&v.to_le_bytes());
        self
    }

    /// A `float32`.
    pub fn f32(&mut self, v: f32) -> &mut Self {
        self.align(4);
        self.buf.extend_from_slice(&v.to_le_bytes());
        self
    }

    /// A `float64`.
    pub fn f64(&mut self, v: f64) -> &mut Self {
        self.align(8);
        self.buf.extend_from_slice(&v.to_le_bytes());
        self
    }

    /// A `string`: length with the terminating NUL, the UTF-8 bytes, NUL.
    pub fn string(&mut self, s: &str) -> &mut Self {
        let n = u32::try_from(s.len() + 1).expect("strings shorter than 4 GiB");
        self.u32(n);
        self.buf.extend_from_slice(s.as_bytes());
        self.buf.push(0);
        self
    }

    /// The element count of a sequence (`T[]`); the caller writes the elements next.
    pub fn seq_len(&mut self, n: usize) -> &mut Self {
        self.u32(u32::try_from(n).expect("sequences shorter than 2^32"))
    }

    /// A `float32[]`.
    pub fn f32_seq(&mut self, v: &[f32]) -> &mut Self {
        self.seq_len(v.len());
        for &x in v {
            self.f32(x);
        }
        self
    }

    /// An `int8[]`.
    pub fn i8_seq(&mut self, v: &[i8]) -> &mut Self {
        self.seq_len(v.len());
        self.buf.extend(v.iter().map(|&x| x as u8));
        self
    }

    /// A `uint8[]`.
    pub fn u8_seq(&mut self, v: &[u8]) -> &mut Self {
        self.seq_len(v.len());
        self.buf.extend_from_slice(v);
        self
    }

    /// A `float64[N]` (a fixed array: no count).
    pub fn f64_array(&mut self, v: &[f64]) -> &mut Self {
        for &x in v {
            self.f64(x);
        }
        self
    }

    /// The message's bytes.
    pub fn finish(self) -> Vec<u8> {
        self.buf
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn header_then_aligned_primitives() {
        let mut w = CdrWriter::new();
        w.u8(7).u32(0x0102_0304).f64(1.5);
        let b = w.finish();
        // header, u8 at 0, pad to 4, u32 at 4..8, f64 at 8..16 (already aligned).
        assert_eq!(&b[..4], &CDR_LE);
        assert_eq!(b[4], 7);
        assert_eq!(&b[5..8], &[0, 0, 0]);
        assert_eq!(&b[8..12], &[4, 3, 2, 1]);
        assert_eq!(&b[12..20], &1.5f64.to_le_bytes());
        assert_eq!(b.len(), 20);
    }

    #[test]
    fn f64_aligns_to_eight_from_the_end_of_the_header() {
        let mut w = CdrWriter::new();
        w.i32(-1).f64(2.0);
        let b = w.finish();
        // i32 at 0..4, four bytes of padding, f64 at 8..16.
        assert_eq!(&b[4..8], &(-1i32).to_le_bytes());
        assert_eq!(&b[8..12], &[0, 0, 0, 0]);
        assert_eq!(&b[12..20], &2.0f64.to_le_bytes());
    }

    #[test]
    fn strings_count_their_nul_and_sequences_their_elements() {
        let mut w = CdrWriter::new();
        w.string("map")
            .string("")
            .f32_seq(&[1.0, f32::NAN])
            .i8_seq(&[-1, 100]);
        let b = w.finish();
        let body = &b[4..];
        assert_eq!(&body[..4], &4u32.to_le_bytes());
        assert_eq!(&body[4..8], b"map\0");
        assert_eq!(&body[8..12], &1u32.to_le_bytes());
        assert_eq!(body[12], 0);
        // pad 13..16, count at 16, floats at 20 and 24.
        assert_eq!(&body[13..16], &[0, 0, 0]);
        assert_eq!(&body[16..20], &2u32.to_le_bytes());
        assert_eq!(&body[20..24], &1.0f32.to_le_bytes());
        assert!(f32::from_le_bytes(body[24..28].try_into().unwrap()).is_nan());
        assert_eq!(&body[28..32], &2u32.to_le_bytes());
        assert_eq!(&body[32..34], &[0xff, 100]);
        assert_eq!(body.len(), 34);
    }

    #[test]
    fn fixed_arrays_have_no_count() {
        let mut w = CdrWriter::new();
        w.bool(true).f64_array(&[0.0; 2]);
        let b = w.finish();
        assert_eq!(b.len(), 4 + 8 + 16);
        assert_eq!(b[4], 1);
    }
}
