//! The ROS 2 messages of a recording written as CDR ([`crate::cdr`]), field by field in the
//! order of their definitions ([`crate::schema`]). Poses are planar: z = 0, a yaw about z.

use crate::cdr::CdrWriter;

/// A time stamp, nanoseconds since the Unix epoch.
pub type Stamp = u64;

fn time(w: &mut CdrWriter, t: Stamp) {
    w.i32((t / 1_000_000_000) as i32)
        .u32((t % 1_000_000_000) as u32);
}

fn header(w: &mut CdrWriter, t: Stamp, frame: &str) {
    time(w, t);
    w.string(frame);
}

/// The quaternion `[x, y, z, w]` of a rotation by `yaw` about z.
pub fn yaw_quaternion(yaw: f64) -> [f64; 4] {
    let (s, c) = (yaw / 2.0).sin_cos();
    [0.0, 0.0, s, c]
}

fn pose(w: &mut CdrWriter, x: f64, y: f64, yaw: f64) {
    w.f64(x).f64(y).f64(0.0);
    for q in yaw_quaternion(yaw) {
        w.f64(q);
    }
}

/// A planar pose in a frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose2 {
    /// x, metres.
    pub x: f64,
    /// y, metres.
    pub y: f64,
    /// Yaw, radians.
    pub yaw: f64,
}

/// `sensor_msgs/msg/LaserScan`: beams from `angle_min` every `increment`, `ranges` in order.
#[derive(Debug, Clone, PartialEq)]
pub struct LaserScan<'a> {
    /// Stamp.
    pub stamp: Stamp,
    /// The sensor's frame.
    pub frame: &'a str,
    /// First beam's angle, radians.
    pub angle_min: f32,
    /// Angle between beams, radians.
    pub increment: f32,
    /// Time between scans, seconds.
    pub scan_time: f32,
    /// Largest range, metres.
    pub range_max: f32,
    /// One range per beam (NaN: no beam there).
    pub ranges: &'a [f32],
}

impl LaserScan<'_> {
    /// The CDR bytes.
    pub fn encode(&self) -> Vec<u8> {
        let mut w = CdrWriter::new();
        header(&mut w, self.stamp, self.frame);
        let angle_max = self.angle_min + self.increment * (self.ranges.len().max(1) - 1) as f32;
        w.f32(self.angle_min)
            .f32(angle_max)
            .f32(self.increment)
            .f32(0.0)
            .f32(self.scan_time)
            .f32(0.0)
            .f32(self.range_max)
            .f32_seq(self.ranges)
            .f32_seq(&[]);
        w.finish()
    }
}

/// `nav_msgs/msg/Odometry` with zero covariances.
#[derive(Debug, Clone, PartialEq)]
pub struct Odometry<'a> {
    /// Stamp.
    pub stamp: Stamp,
    /// Pose frame (`odom`).
    pub frame: &'a str,
    /// Body frame (`<robot>/base_link`), in which the twist is given.
    pub child: &'a str,
    /// Pose.
    pub pose: Pose2,
    /// Forward speed, m/s.
    pub speed: f64,
    /// Turn rate, rad/s.
    pub omega: f64,
}

impl Odometry<'_> {
    /// The CDR bytes.
    pub fn encode(&self) -> Vec<u8> {
        let mut w = CdrWriter::new();
        header(&mut w, self.stamp, self.frame);
        w.string(self.child);
        pose(&mut w, self.pose.x, self.pose.y, self.pose.yaw);
        w.f64_array(&[0.0; 36]);
        w.f64(self.speed).f64(0.0).f64(0.0);
        w.f64(0.0).f64(0.0).f64(self.omega);
        w.f64_array(&[0.0; 36]);
        w.finish()
    }
}

/// One `geometry_msgs/msg/TransformStamped`.
#[derive(Debug, Clone, PartialEq)]
pub struct Transform<'a> {
    /// Stamp.
    pub stamp: Stamp,
    /// Parent frame.
    pub parent: &'a str,
    /// Child frame.
    pub child: &'a str,
    /// The child's pose in the parent.
    pub pose: Pose2,
}

/// `tf2_msgs/msg/TFMessage`.
pub fn tf_message(transforms: &[Transform<'_>]) -> Vec<u8> {
    let mut w = CdrWriter::new();
    w.seq_len(transforms.len());
    for t in transforms {
        header(&mut w, t.stamp, t.parent);
        w.string(t.child);
        pose(&mut w, t.pose.x, t.pose.y, t.pose.yaw);
    }
    w.finish()
}

/// `nav_msgs/msg/OccupancyGrid`: `data` row-major from the cell at `origin`, rows along +y;
/// 0 free, 100 occupied, -1 unknown.
#[derive(Debug, Clone, PartialEq)]
pub struct OccupancyGrid<'a> {
    /// Stamp (also the map's load time).
    pub stamp: Stamp,
    /// Frame (`map`).
    pub frame: &'a str,
    /// Cell size, metres.
    pub resolution: f32,
    /// Columns.
    pub width: u32,
    /// Rows.
    pub height: u32,
    /// The lower-left corner of cell (0, 0).
    pub origin: Pose2,
    /// Cells.
    pub data: &'a [i8],
}

impl OccupancyGrid<'_> {
    /// The CDR bytes.
    pub fn encode(&self) -> Vec<u8> {
        let mut w = CdrWriter::new();
        header(&mut w, self.stamp, self.frame);
        time(&mut w, self.stamp);
        w.f32(self.resolution).u32(self.width).u32(self.height);
        pose(&mut w, self.origin.x, self.origin.y, self.origin.yaw);
        w.i8_seq(self.data);
        w.finish()
    }
}

/// `visualization_msgs/msg/Marker` types used here.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MarkerKind {
    /// A closed or open polyline through `points`.
    LineStrip = 4,
    /// Segments between consecutive pairs of `points`.
    LineList = 5,
    /// `text` facing the viewer at the pose.
    Text = 9,
}

/// One `visualization_msgs/msg/Marker` (action ADD, forever, identity orientation, no texture
/// or mesh).
#[derive(Debug, Clone, PartialEq)]
pub struct Marker {
    /// Namespace.
    pub ns: String,
    /// Id within the namespace.
    pub id: i32,
    /// Type.
    pub kind: MarkerKind,
    /// Position of the pose.
    pub position: [f64; 3],
    /// Scale (line width in x; text height in z).
    pub scale: [f64; 3],
    /// RGBA, 0-1.
    pub color: [f32; 4],
    /// Points, in the frame.
    pub points: Vec<[f64; 3]>,
    /// Text.
    pub text: String,
}

/// `visualization_msgs/msg/MarkerArray` of `markers`, all in `frame`.
pub fn marker_array(stamp: Stamp, frame: &str, markers: &[Marker]) -> Vec<u8> {
    let mut w = CdrWriter::new();
    w.seq_len(markers.len());
    for m in markers {
        header(&mut w, stamp, frame);
        w.string(&m.ns).i32(m.id).i32(m.kind as i32).i32(0);
        w.f64(m.position[0]).f64(m.position[1]).f64(m.position[2]);
        w.f64(0.0).f64(0.0).f64(0.0).f64(1.0);
        w.f64(m.scale[0]).f64(m.scale[1]).f64(m.scale[2]);
        for c in m.color {
            w.f32(c);
        }
        w.i32(0).u32(0); // lifetime: forever
        w.bool(false); // frame_locked
        w.seq_len(m.points.len());
        for p in &m.points {
            w.f64(p[0]).f64(p[1]).f64(p[2]);
        }
        w.seq_len(0); // colors
        w.string(""); // texture_resource
        header(&mut w, 0, ""); // texture: CompressedImage
        w.string("").u8_seq(&[]);
        w.seq_len(0); // uv_coordinates
        w.string(&m.text);
        w.string(""); // mesh_resource
        w.string("").u8_seq(&[]); // mesh_file
        w.bool(false); // mesh_use_embedded_materials
    }
    w.finish()
}

/// `std_msgs/msg/String`.
pub fn string(s: &str) -> Vec<u8> {
    let mut w = CdrWriter::new();
    w.string(s);
    w.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stamps_split_into_seconds_and_nanoseconds() {
        let b = string("x");
        assert_eq!(b, [0, 1, 0, 0, 2, 0, 0, 0, b'x', 0]);
        let mut w = CdrWriter::new();
        header(&mut w, 1_700_000_000_250_000_000, "map");
        let b = w.finish();
        assert_eq!(&b[4..8], &1_700_000_000i32.to_le_bytes());
        assert_eq!(&b[8..12], &250_000_000u32.to_le_bytes());
        assert_eq!(&b[12..16], &4u32.to_le_bytes());
        assert_eq!(&b[16..20], b"map\0");
    }

    #[test]
    fn yaw_quaternions_are_unit_and_about_z() {
        let q = yaw_quaternion(std::f64::consts::FRAC_PI_2);
        assert!((q[2] - 0.5f64.sqrt()).abs() < 1e-12 && (q[3] - 0.5f64.sqrt()).abs() < 1e-12);
        assert_eq!(yaw_quaternion(0.0), [0.0, 0.0, 0.0, 1.0]);
    }

    #[test]
    fn laser_scan_sizes_and_angle_max() {
        let ranges = [1.0f32, f32::NAN, 2.0, 3.0, 4.0, f32::NAN, 5.0];
        let b = LaserScan {
            stamp: 0,
            frame: "r/base_link",
            angle_min: -1.5,
            increment: 0.5,
            scan_time: 0.1,
            range_max: 5.0,
            ranges: &ranges,
        }
        .encode();
        // header: 8 (time) + 4 + 12 ("r/base_link\0") = 24; 7 floats = 28; counts 4 + 28 + 4.
        assert_eq!(b.len(), 4 + 24 + 28 + 4 + 28 + 4);
        let angle_max = f32::from_le_bytes(b[4 + 28..4 + 32].try_into().unwrap());
        assert_eq!(angle_max, 1.5);
    }
}
