//! The topic's snapshot: the plan around what it is about, drawn from the profile's occupancy
//! grid of that storey (free white, occupied dark, unknown grey), north up, with the door,
//! stair or space filled in its status colour and the viewpoint's camera as a blue dot with
//! its line of sight. PNG, [`WIDTH`] x [`HEIGHT`] pixels.

use glam::DVec2;
use poinav_nav::grid::{CellState, OccupancyGrid};
use poinav_nav::polygon;

use crate::issue::{rings_bounds, Focus};
use crate::BcfError;

/// Snapshot width, pixels.
pub const WIDTH: u32 = 640;
/// Snapshot height, pixels.
pub const HEIGHT: u32 = 480;
/// The smallest width of plan shown, metres (the height follows the aspect ratio).
pub const MIN_SPAN_M: f64 = 8.0;

type Rgb = [u8; 3];

const FREE: Rgb = [255, 255, 255];
const OCCUPIED: Rgb = [64, 64, 64];
const UNKNOWN: Rgb = [205, 205, 205];
const CAMERA: Rgb = [26, 115, 232];
// The audit drawings' colours (poinav-nav's svg.rs).
const RESTRICTED: Rgb = [0xe8, 0xa4, 0x00];
const BLOCKED: Rgb = [0xd9, 0x30, 0x25];
const UNREACHABLE_FILL: Rgb = [0xf5, 0xc4, 0xbf];

/// The colour of a status word (`RESTRICTED`, else the BLOCKED red).
fn status_colour(status: &str) -> Rgb {
    if status == "RESTRICTED" {
        RESTRICTED
    } else {
        BLOCKED
    }
}

/// The plan window shown: lower-left corner and metres per pixel.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Window {
    /// World position of the lower-left corner.
    pub origin: DVec2,
    /// Metres per pixel.
    pub scale: f64,
}

impl Window {
    /// The window centred on what `focus` is about, [`MIN_SPAN_M`] wide or wider to hold a
    /// space with a metre around it.
    pub fn around(focus: &Focus) -> Window {
        let (lo, hi) = match focus {
            Focus::Door { center, .. } => (*center, *center),
            Focus::Landing {
                landing, target, ..
            } => (landing.min(*target), landing.max(*target)),
            Focus::Space { ring } => {
                rings_bounds(std::slice::from_ref(ring)).unwrap_or((DVec2::ZERO, DVec2::ZERO))
            }
        };
        let center = (lo + hi) / 2.0;
        let need = (hi - lo) + DVec2::splat(2.0);
        let aspect = f64::from(WIDTH) / f64::from(HEIGHT);
        let span = MIN_SPAN_M.max(need.x).max(need.y * aspect);
        let scale = span / f64::from(WIDTH);
        let half = DVec2::new(f64::from(WIDTH), f64::from(HEIGHT)) * scale / 2.0;
        Window {
            origin: center - half,
            scale,
        }
    }

    /// World position of the centre of pixel (`col`, `row`), row 0 at the top.
    pub fn point(&self, col: u32, row: u32) -> DVec2 {
        DVec2::new(
            self.origin.x + (f64::from(col) + 0.5) * self.scale,
            self.origin.y + (f64::from(HEIGHT - row) - 0.5) * self.scale,
        )
    }
}

/// The snapshot as RGB pixels, rows from the top.
pub fn render(
    grid: &OccupancyGrid,
    focus: &Focus,
    status: &str,
    camera: Option<(DVec2, DVec2)>,
) -> Vec<u8> {
    let window = Window::around(focus);
    let colour = status_colour(status);
    let line = window.scale * 1.5;
    let mut px: Vec<Rgb> = Vec::with_capacity((WIDTH * HEIGHT) as usize);
    for row in 0..HEIGHT {
        for col in 0..WIDTH {
            px.push(
                match grid.cell_of(window.point(col, row)).map(|i| grid.cells[i]) {
                    Some(CellState::Free) => FREE,
                    Some(CellState::Occupied) => OCCUPIED,
                    _ => UNKNOWN,
                },
            );
        }
    }
    // Overlays, each over the pixels of its own bounding box only.
    let margin = DVec2::splat(line);
    match focus {
        Focus::Door { ring, center, .. } => {
            if let Some((lo, hi)) = rings_bounds(std::slice::from_ref(ring)) {
                each_pixel_in(&window, lo - margin, hi + margin, |i, p| {
                    if polygon::contains(ring, p) {
                        px[i] = colour;
                    } else if polygon::boundary_distance(ring, p) < line {
                        px[i] = darker(colour);
                    }
                });
            }
            // A circle 0.7 m around the door finds it at a glance.
            let r1 = 0.7 + 2.0 * window.scale;
            each_pixel_in(
                &window,
                *center - DVec2::splat(r1),
                *center + DVec2::splat(r1),
                |i, p| {
                    let r = p.distance(*center);
                    if r > 0.7 && r < r1 {
                        px[i] = colour;
                    }
                },
            );
        }
        Focus::Landing { rings, landing, .. } => {
            if let Some((lo, hi)) = rings_bounds(rings) {
                each_pixel_in(&window, lo - margin, hi + margin, |i, p| {
                    if rings.iter().any(|r| polygon::contains(r, p)) {
                        px[i] = blend(px[i], colour);
                    } else if rings
                        .iter()
                        .any(|r| polygon::boundary_distance(r, p) < line)
                    {
                        px[i] = darker(colour);
                    }
                });
            }
            disc(
                &window,
                &mut px,
                *landing,
                4.0 * window.scale,
                darker(colour),
            );
        }
        Focus::Space { ring } => {
            if let Some((lo, hi)) = rings_bounds(std::slice::from_ref(ring)) {
                each_pixel_in(&window, lo - margin, hi + margin, |i, p| {
                    if polygon::boundary_distance(ring, p) < line {
                        px[i] = BLOCKED;
                    } else if px[i] == FREE && polygon::contains(ring, p) {
                        px[i] = UNREACHABLE_FILL;
                    }
                });
            }
        }
    }
    if let Some((eye, dir)) = camera {
        let end = eye + dir.normalize_or_zero() * 1.2;
        let m = DVec2::splat(window.scale);
        each_pixel_in(&window, eye.min(end) - m, eye.max(end) + m, |i, p| {
            if polygon::segment_distance(eye, end, p) < window.scale {
                px[i] = CAMERA;
            }
        });
        disc(&window, &mut px, eye, 5.0 * window.scale, CAMERA);
    }
    px.into_iter().flatten().collect()
}

/// Paints the pixels within `radius` of `center`.
fn disc(window: &Window, px: &mut [Rgb], center: DVec2, radius: f64, colour: Rgb) {
    let r = DVec2::splat(radius);
    each_pixel_in(window, center - r, center + r, |i, p| {
        if p.distance(center) < radius {
            px[i] = colour;
        }
    });
}

/// Calls `f` with the index and centre of every pixel of `window` whose centre may lie in the
/// box `lo`..`hi` (world metres).
fn each_pixel_in(window: &Window, lo: DVec2, hi: DVec2, mut f: impl FnMut(usize, DVec2)) {
    let (w, h) = (f64::from(WIDTH), f64::from(HEIGHT));
    let col = |x: f64| ((x - window.origin.x) / window.scale).clamp(0.0, w);
    let row = |y: f64| (h - (y - window.origin.y) / window.scale).clamp(0.0, h);
    let (c0, c1) = (col(lo.x).floor() as u32, col(hi.x).ceil() as u32);
    let (r0, r1) = (row(hi.y).floor() as u32, row(lo.y).ceil() as u32);
    for r in r0..r1.min(HEIGHT) {
        for c in c0..c1.min(WIDTH) {
            f((r * WIDTH + c) as usize, window.point(c, r));
        }
    }
}

fn darker(c: Rgb) -> Rgb {
    c.map(|v| (u16::from(v) * 2 / 3) as u8)
}

fn blend(a: Rgb, b: Rgb) -> Rgb {
    [0, 1, 2].map(|i| ((u16::from(a[i]) + u16::from(b[i])) / 2) as u8)
}

/// `pixels` (RGB, [`WIDTH`] x [`HEIGHT`]) as PNG bytes; `name` is for errors.
pub fn png(pixels: &[u8], name: &str) -> Result<Vec<u8>, BcfError> {
    let err = |source| BcfError::Png {
        name: name.to_string(),
        source,
    };
    let mut out = Vec::new();
    {
        let mut encoder = png::Encoder::new(&mut out, WIDTH, HEIGHT);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        let mut writer = encoder.write_header().map_err(err)?;
        writer.write_image_data(pixels).map_err(err)?;
        writer.finish().map_err(err)?;
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_door_window_is_eight_metres_wide_centred_on_it_north_up() {
        let focus = Focus::Door {
            ring: Default::default(),
            center: DVec2::new(10.0, 20.0),
            normal: DVec2::X,
        };
        let w = Window::around(&focus);
        assert!((w.scale - 8.0 / 640.0).abs() < 1e-12);
        assert!((w.origin - DVec2::new(6.0, 17.0)).length() < 1e-9, "{w:?}");
        // Top-left pixel is north-west, bottom-right south-east.
        let nw = w.point(0, 0);
        let se = w.point(WIDTH - 1, HEIGHT - 1);
        assert!(nw.x < 6.1 && nw.y > 22.9, "{nw}");
        assert!(se.x > 13.9 && se.y < 17.1, "{se}");
    }

    #[test]
    fn a_large_space_widens_the_window() {
        let ring = poinav_nav::polygon::rect(0.0, 0.0, 20.0, 5.0);
        let w = Window::around(&Focus::Space { ring });
        // 20 m plus a metre each side.
        assert!((w.scale * f64::from(WIDTH) - 22.0).abs() < 1e-9, "{w:?}");
    }
}
