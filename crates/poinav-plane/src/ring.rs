//! [`Ring`]: an owned closed polygon (its points in order, the closing edge implied), which
//! reads as a `&[DVec2]` wherever the plane functions take one and serialises as its point
//! list, so a floor that holds rings is written as before.

use std::ops::{Deref, DerefMut};

use glam::DVec2;
use serde::{Deserialize, Serialize};

/// A closed polygon as its points in order (world metres where a floor holds it; the last
/// point is not repeated). Derefs to `[DVec2]` (its points can be moved, not added or
/// removed); serialised transparently as the list.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(transparent)]
pub struct Ring(Vec<DVec2>);

impl Ring {
    /// The ring's points.
    #[inline]
    pub fn as_slice(&self) -> &[DVec2] {
        &self.0
    }

    /// The point list.
    #[inline]
    pub fn into_vec(self) -> Vec<DVec2> {
        self.0
    }
}

impl Deref for Ring {
    type Target = [DVec2];

    #[inline]
    fn deref(&self) -> &[DVec2] {
        &self.0
    }
}

impl DerefMut for Ring {
    #[inline]
    fn deref_mut(&mut self) -> &mut [DVec2] {
        &mut self.0
    }
}

impl AsRef<[DVec2]> for Ring {
    #[inline]
    fn as_ref(&self) -> &[DVec2] {
        &self.0
    }
}

impl From<Vec<DVec2>> for Ring {
    #[inline]
    fn from(points: Vec<DVec2>) -> Ring {
        Ring(points)
    }
}

impl From<&[DVec2]> for Ring {
    #[inline]
    fn from(points: &[DVec2]) -> Ring {
        Ring(points.to_vec())
    }
}

impl From<Ring> for Vec<DVec2> {
    #[inline]
    fn from(ring: Ring) -> Vec<DVec2> {
        ring.0
    }
}

impl FromIterator<DVec2> for Ring {
    fn from_iter<I: IntoIterator<Item = DVec2>>(iter: I) -> Ring {
        Ring(iter.into_iter().collect())
    }
}

impl<'a> IntoIterator for &'a Ring {
    type Item = &'a DVec2;
    type IntoIter = std::slice::Iter<'a, DVec2>;

    #[inline]
    fn into_iter(self) -> Self::IntoIter {
        self.0.iter()
    }
}

impl<'a> IntoIterator for &'a mut Ring {
    type Item = &'a mut DVec2;
    type IntoIter = std::slice::IterMut<'a, DVec2>;

    #[inline]
    fn into_iter(self) -> Self::IntoIter {
        self.0.iter_mut()
    }
}

/// The axis-aligned rectangle `[x0, x1] x [y0, y1]` as a counter-clockwise ring.
pub fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Ring {
    Ring(vec![
        DVec2::new(x0, y0),
        DVec2::new(x1, y0),
        DVec2::new(x1, y1),
        DVec2::new(x0, y1),
    ])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_ring_serialises_as_its_point_list() {
        let r = rect(0.0, 0.0, 2.0, 1.5);
        let points: Vec<DVec2> = r.clone().into();
        assert_eq!(
            serde_json::to_string(&r).unwrap(),
            serde_json::to_string(&points).unwrap()
        );
        assert_eq!(
            serde_json::to_string(&r).unwrap(),
            "[[0.0,0.0],[2.0,0.0],[2.0,1.5],[0.0,1.5]]"
        );
        let back: Ring = serde_json::from_str("[[0.0,0.0],[2.0,0.0],[2.0,1.5]]").unwrap();
        assert_eq!(back.len(), 3);
        assert_eq!(back[1], DVec2::new(2.0, 0.0));
        assert_eq!(Ring::from(points.clone()).as_slice(), &points[..]);
    }
}
