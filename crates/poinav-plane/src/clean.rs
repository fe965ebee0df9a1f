//! Rings cleaned for geometry: repeated points (the closing one too) dropped, and made
//! counter-clockwise with an area, or refused.

use glam::DVec2;

use crate::measure::{bounds, signed_area};

/// Drops repeated points (the closing one too) and makes the polygon counter-clockwise;
/// `None` when fewer than three points remain, a point is not finite, or it has no area.
pub fn clean(points: Vec<DVec2>) -> Option<Vec<DVec2>> {
    let (lo, hi) = bounds(&points)?;
    let mut out = without_repeats(points)?;
    let a = signed_area(&out);
    let extent = (hi - lo).max_element();
    if a.abs() <= 1e-12 * extent * extent {
        return None;
    }
    if a < 0.0 {
        out.reverse();
    }
    Some(out)
}

/// The ring without repeated points (within a billionth of its extent; the closing point
/// too); `None` when fewer than three points remain or a point is not finite.
pub fn without_repeats(points: Vec<DVec2>) -> Option<Vec<DVec2>> {
    if points.iter().any(|p| !p.is_finite()) {
        return None;
    }
    let (lo, hi) = bounds(&points)?;
    let eps = 1e-9 * (hi - lo).max_element().max(1e-300);
    let mut out: Vec<DVec2> = Vec::with_capacity(points.len());
    for p in points {
        if out.last().is_none_or(|q| q.distance(p) > eps) {
            out.push(p);
        }
    }
    while out.len() > 1 && out[0].distance(*out.last().expect("non-empty")) <= eps {
        out.pop();
    }
    (out.len() >= 3).then_some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clean_drops_repeats_and_turns_clockwise_rings() {
        let cw = vec![
            DVec2::new(0.0, 0.0),
            DVec2::new(0.0, 2.0),
            DVec2::new(0.0, 2.0),
            DVec2::new(3.0, 2.0),
            DVec2::new(3.0, 0.0),
            DVec2::new(0.0, 0.0),
        ];
        let c = clean(cw).unwrap();
        assert_eq!(c.len(), 4);
        assert_eq!(signed_area(&c), 6.0);
        assert_eq!(
            clean(vec![DVec2::ZERO, DVec2::X, DVec2::X * 2.0]),
            None,
            "no area"
        );
        assert_eq!(clean(vec![]), None);
        assert_eq!(
            without_repeats(vec![DVec2::ZERO, DVec2::NAN, DVec2::X]),
            None
        );
    }
}
