//! Numbers as text, deterministic and without the general formatter where it can be avoided:
//! [`fixed`] decimals (no `-0`, no trailing zeros, `null` when not finite) and integers, written
//! into any [`Text`] (a `String`, or bytes such as a trace line). The simulator's trace and plots
//! and the plan drawings (`poinav-export`) format their numbers here.

/// Text being written: a `String`, or bytes (the simulator's trace lines).
pub trait Text {
    /// Appends `s`.
    fn put(&mut self, s: &str);
    /// Appends ASCII bytes.
    fn put_ascii(&mut self, b: &[u8]);
    /// Appends the first `n` bytes of `buf` (ASCII).
    fn put_head<const N: usize>(&mut self, buf: &[u8; N], n: usize) {
        self.put_ascii(&buf[..n]);
    }
}

impl Text for String {
    fn put(&mut self, s: &str) {
        self.push_str(s);
    }

    fn put_ascii(&mut self, b: &[u8]) {
        self.push_str(std::str::from_utf8(b).unwrap_or_default());
    }
}

impl Text for Vec<u8> {
    // Inlined: a literal's length is then known where it is copied, so the copy is a few moves
    // instead of a call to `memcpy`.
    #[inline]
    fn put(&mut self, s: &str) {
        self.extend_from_slice(s.as_bytes());
    }

    #[inline]
    fn put_ascii(&mut self, b: &[u8]) {
        self.extend_from_slice(b);
    }

    /// The whole buffer copied, the tail cut off: a copy of a size known when compiling is a
    /// few moves, one of a size known only when running a call to `memmove` (a quarter of the
    /// trace's time went there).
    #[inline]
    fn put_head<const N: usize>(&mut self, buf: &[u8; N], n: usize) {
        let len = self.len();
        self.extend_from_slice(buf);
        self.truncate(len + n.min(N));
    }
}

/// `v` with at most `decimals` decimals, deterministic: no `-0`, no trailing zeros.
pub fn fixed(v: f64, decimals: usize) -> String {
    let mut s = String::new();
    push_fixed(&mut s, v, decimals);
    s
}

const POW10: [f64; 7] = [1.0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6];

/// Two-digit pieces "00" to "99".
const PAIRS: &[u8; 200] = b"\
0001020304050607080910111213141516171819\
2021222324252627282930313233343536373839\
4041424344454647484950515253545556575859\
6061626364656667686970717273747576777879\
8081828384858687888990919293949596979899";

/// Appends the decimal digits of `v`, zero-padded to at least `width` digits (at most 20),
/// without the general formatter.
pub fn push_digits<T: Text>(out: &mut T, v: u64, width: usize) {
    // Written from the back (two digits at a time) to end at index 20, then the text's 20
    // bytes from its first digit copied to the head of a fixed-size buffer: no count of the
    // digits first, and a copy of a size known when compiling.
    let mut back = [b'0'; 40];
    let i = put_back(&mut back, 20, v).min(20 - width.clamp(1, 20));
    let mut head = [0u8; 20];
    head.copy_from_slice(&back[i..i + 20]);
    out.put_head(&head, 20 - i);
}

/// Writes the digits of `v` (at least one) into `buf` ending before `end`, two at a time from
/// the back; returns where they begin.
#[inline]
fn put_back(buf: &mut [u8], end: usize, mut v: u64) -> usize {
    let mut i = end;
    while v >= 100 {
        i -= 2;
        put_pair(buf, i, v % 100);
        v /= 100;
    }
    if v >= 10 {
        i -= 2;
        put_pair(buf, i, v);
    } else {
        i -= 1;
        buf[i] = b'0' + v as u8;
    }
    i
}

/// Writes the two digits of `v` (below 100) at `buf[i..i + 2]`.
#[inline]
fn put_pair(buf: &mut [u8], i: usize, v: u64) {
    let k = v as usize * 2;
    buf[i..i + 2].copy_from_slice(&PAIRS[k..k + 2]);
}

/// Appends `m / 10^decimals` (`m` > 0 and at most 10^16, `decimals` at most 6) with the
/// fraction's trailing zeros, and a bare point, trimmed. One pass from the back, dividing by
/// constants only (the integer and fractional parts apart take two divisions by a power of ten
/// known only when running, each a slow instruction), then copied to the head of a fixed-size
/// buffer for [`Text::put_head`].
fn push_scaled<T: Text>(out: &mut T, mut m: u64, decimals: usize) {
    // The text ends before index 24: the integer digits, the point, the fraction's digits.
    let mut back = [b'0'; 48];
    let point = 23 - decimals;
    let mut i = 24;
    let mut left = decimals;
    while left >= 2 {
        i -= 2;
        put_pair(&mut back, i, m % 100);
        m /= 100;
        left -= 2;
    }
    if left == 1 {
        i -= 1;
        back[i] = b'0' + (m % 10) as u8;
        m /= 10;
    }
    let mut end = 24;
    while end > point + 1 && back[end - 1] == b'0' {
        end -= 1;
    }
    if end == point + 1 {
        end = point;
    }
    back[point] = b'.';
    let i = put_back(&mut back, point, m);
    let mut head = [0u8; 24];
    head.copy_from_slice(&back[i..i + 24]);
    out.put_head(&head, end - i);
}

/// Appends `v` as `format!("{v}")` writes it.
pub fn push_int<T: Text>(out: &mut T, v: i64) {
    if v < 0 {
        out.put_ascii(b"-");
    }
    push_digits(out, v.unsigned_abs(), 1);
}

/// Appends [`fixed`]`(v, decimals)` to `out`. The same digits as `format!("{v:.decimals$}")`
/// (the exact binary value correctly rounded), trimmed; the common case without the general
/// formatter: `v` scaled by `10^decimals` in `f64` is off the exact product by at most half an
/// ulp, so when it is farther than that from a rounding boundary (half an integer) it rounds
/// like the exact product, and the integer is printed.
pub fn push_fixed<T: Text>(out: &mut T, v: f64, decimals: usize) {
    if !v.is_finite() {
        out.put_ascii(b"null");
        return;
    }
    if decimals < POW10.len() {
        let x = v * POW10[decimals];
        if x.abs() < 1e15 {
            // floor(x) without a libm call: truncation, one less below zero.
            let t = x as i64;
            let floor = if (t as f64) > x { t - 1 } else { t };
            let frac = x - floor as f64;
            let margin = x.abs() * 2.3e-16 + 1e-300;
            if (frac - 0.5).abs() > margin {
                // Not at a tie: rounding half away from zero is rounding to the nearer one.
                let m = if frac > 0.5 { floor + 1 } else { floor };
                if m == 0 {
                    out.put_ascii(b"0");
                    return;
                }
                if m < 0 {
                    out.put_ascii(b"-");
                }
                push_scaled(out, m.unsigned_abs(), decimals);
                return;
            }
        }
    }
    let mut s = format!("{v:.decimals$}");
    if s.contains('.') {
        while s.ends_with('0') {
            s.pop();
        }
        if s.ends_with('.') {
            s.pop();
        }
    }
    out.put(if s == "-0" { "0" } else { &s });
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integers_are_written_as_the_general_formatter_writes_them() {
        let mut seed = 0x0123_4567_89AB_CDEFu64;
        let mut values = vec![
            0i64,
            1,
            -1,
            9,
            10,
            -10,
            99,
            100,
            i64::MAX,
            i64::MIN,
            1 << 53,
        ];
        for _ in 0..10_000 {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            values.push((seed as i64) >> (seed % 63));
        }
        for v in values {
            let mut s = String::new();
            push_int(&mut s, v);
            assert_eq!(s, v.to_string());
        }
        let mut s = String::new();
        push_digits(&mut s, 42, 5);
        assert_eq!(s, "00042");
    }

    #[test]
    fn numbers_are_fixed_and_signless_at_zero() {
        assert_eq!(fixed(-0.0000001, 6), "0");
        assert_eq!(fixed(1.5, 6), "1.5");
        assert_eq!(fixed(2.0, 6), "2");
        assert_eq!(fixed(-3.1234567, 6), "-3.123457");
        assert_eq!(fixed(f64::NAN, 6), "null");
        // A plan drawing's millimetres.
        assert_eq!(fixed(1.0, 3), "1");
        assert_eq!(fixed(-0.0001, 3), "0");
        assert_eq!(fixed(2.5004, 3), "2.5");
        assert_eq!(fixed(-3.1226, 3), "-3.123");
    }

    /// The general formatter's digits, trimmed (what `fixed` wrote before its fast path).
    fn reference(v: f64, decimals: usize) -> String {
        if !v.is_finite() {
            return "null".into();
        }
        let mut s = format!("{v:.decimals$}");
        if s.contains('.') {
            while s.ends_with('0') {
                s.pop();
            }
            if s.ends_with('.') {
                s.pop();
            }
        }
        if s == "-0" {
            s = "0".into();
        }
        s
    }

    #[test]
    fn fast_fixed_numbers_equal_the_general_formatter() {
        let mut seed = 0x9E37_79B9_7F4A_7C15u64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        for k in 0..230_000 {
            let r = next();
            let v = match k % 4 {
                // Any magnitude.
                0 => f64::from_bits(r),
                // Poses and speeds.
                1 => (r >> 11) as f64 / (1u64 << 53) as f64 * 200.0 - 100.0,
                // Halves and exact decimals: the rounding boundaries.
                2 => ((r % 2_000_001) as f64 - 1_000_000.0) / 2f64.powi((r >> 40) as i32 % 12),
                _ => ((r % 20_000_001) as f64 - 10_000_000.0) * 1e-7,
            };
            for d in 0usize..=6 {
                assert_eq!(fixed(v, d), reference(v, d), "{v:e} with {d} decimals");
            }
        }
        for v in [
            0.5,
            1.5,
            2.5,
            -0.5,
            0.0000005,
            0.0000015,
            1e15,
            -1e-300,
            5e-7,
            -5e-7,
            -0.0,
            1e-7,
            -1e-7,
            123456789.123456,
            -999999999.9999995,
            -2.5e14,
            9.2e18,
            -1.7e308,
            -3.0,
            7.0,
        ] {
            for d in 0usize..=6 {
                assert_eq!(fixed(v, d), reference(v, d), "{v:e} with {d} decimals");
            }
        }
    }
}
