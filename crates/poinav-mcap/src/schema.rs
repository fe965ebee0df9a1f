//! The ROS 2 message definitions the recordings use, as `ros2msg` schema text the way rosbag2
//! stores it: the message's own fields, then each type it depends on after a line of 80 `=`
//! and a `MSG: package/Type` line. Field lists are those of ROS 2 Jazzy (`Marker` has the
//! texture and mesh-file fields added in Iron); comments are left out.

/// A schema: its name (`package/msg/Type`) and definition text.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Schema {
    /// `sensor_msgs/msg/LaserScan`.
    pub name: &'static str,
    /// The `ros2msg` text.
    pub text: String,
}

const TIME: &str = "int32 sec\nuint32 nanosec\n";
const DURATION: &str = "int32 sec\nuint32 nanosec\n";
const HEADER: &str = "builtin_interfaces/Time stamp\nstring frame_id\n";
const POINT: &str = "float64 x\nfloat64 y\nfloat64 z\n";
const QUATERNION: &str = "float64 x 0\nfloat64 y 0\nfloat64 z 0\nfloat64 w 1\n";
const VECTOR3: &str = "float64 x\nfloat64 y\nfloat64 z\n";
const POSE: &str = "Point position\nQuaternion orientation\n";
const POSE_COV: &str = "Pose pose\nfloat64[36] covariance\n";
const TWIST: &str = "Vector3 linear\nVector3 angular\n";
const TWIST_COV: &str = "Twist twist\nfloat64[36] covariance\n";
const TRANSFORM: &str = "Vector3 translation\nQuaternion rotation\n";
const TRANSFORM_STAMPED: &str =
    "std_msgs/Header header\nstring child_frame_id\nTransform transform\n";
const COLOR: &str = "float32 r\nfloat32 g\nfloat32 b\nfloat32 a\n";
const COMPRESSED_IMAGE: &str = "std_msgs/Header header\nstring format\nuint8[] data\n";
const UV: &str = "float32 u\nfloat32 v\n";
const MESH_FILE: &str = "string filename\nuint8[] data\n";
const MAP_META: &str = "builtin_interfaces/Time map_load_time\nfloat32 resolution\nuint32 width\nuint32 height\ngeometry_msgs/Pose origin\n";

const LASER_SCAN: &str = "std_msgs/Header header\nfloat32 angle_min\nfloat32 angle_max\nfloat32 angle_increment\nfloat32 time_increment\nfloat32 scan_time\nfloat32 range_min\nfloat32 range_max\nfloat32[] ranges\nfloat32[] intensities\n";
const ODOMETRY: &str = "std_msgs/Header header\nstring child_frame_id\ngeometry_msgs/PoseWithCovariance pose\ngeometry_msgs/TwistWithCovariance twist\n";
const TF_MESSAGE: &str = "geometry_msgs/TransformStamped[] transforms\n";
const OCCUPANCY_GRID: &str = "std_msgs/Header header\nMapMetaData info\nint8[] data\n";
const MARKER_ARRAY: &str = "Marker[] markers\n";
const MARKER: &str = "int32 ARROW=0
int32 CUBE=1
int32 SPHERE=2
int32 CYLINDER=3
int32 LINE_STRIP=4
int32 LINE_LIST=5
int32 CUBE_LIST=6
int32 SPHERE_LIST=7
int32 POINTS=8
int32 TEXT_VIEW_FACING=9
int32 MESH_RESOURCE=10
int32 TRIANGLE_LIST=11
int32 ARROW_STRIP=12
int32 ADD=0
int32 MODIFY=0
int32 DELETE=2
int32 DELETEALL=3
std_msgs/Header header
string ns
int32 id
int32 type
int32 action
geometry_msgs/Pose pose
geometry_msgs/Vector3 scale
std_msgs/ColorRGBA color
builtin_interfaces/Duration lifetime
bool frame_locked
geometry_msgs/Point[] points
std_msgs/ColorRGBA[] colors
string texture_resource
sensor_msgs/CompressedImage texture
UVCoordinate[] uv_coordinates
string text
string mesh_resource
MeshFile mesh_file
bool mesh_use_embedded_materials
";
const STRING: &str = "string data\n";

fn with_deps(name: &'static str, main: &str, deps: &[(&str, &str)]) -> Schema {
    let mut text = main.to_string();
    for (dep, body) in deps {
        text.push_str(&"=".repeat(80));
        text.push_str("\nMSG: ");
        text.push_str(dep);
        text.push('\n');
        text.push_str(body);
    }
    Schema { name, text }
}

/// `sensor_msgs/msg/LaserScan`.
pub fn laser_scan() -> Schema {
    with_deps(
        "sensor_msgs/msg/LaserScan",
        LASER_SCAN,
        &[
            ("std_msgs/Header", HEADER),
            ("builtin_interfaces/Time", TIME),
        ],
    )
}

/// `nav_msgs/msg/Odometry`.
pub fn odometry() -> Schema {
    with_deps(
        "nav_msgs/msg/Odometry",
        ODOMETRY,
        &[
            ("std_msgs/Header", HEADER),
            ("builtin_interfaces/Time", TIME),
            ("geometry_msgs/PoseWithCovariance", POSE_COV),
            ("geometry_msgs/Pose", POSE),
            ("geometry_msgs/Point", POINT),
            ("geometry_msgs/Quaternion", QUATERNION),
            ("geometry_msgs/TwistWithCovariance", TWIST_COV),
            ("geometry_msgs/Twist", TWIST),
            ("geometry_msgs/Vector3", VECTOR3),
        ],
    )
}

/// `tf2_msgs/msg/TFMessage`.
pub fn tf_message() -> Schema {
    with_deps(
        "tf2_msgs/msg/TFMessage",
        TF_MESSAGE,
        &[
            ("geometry_msgs/TransformStamped", TRANSFORM_STAMPED),
            ("std_msgs/Header", HEADER),
            ("builtin_interfaces/Time", TIME),
            ("geometry_msgs/Transform", TRANSFORM),
            ("geometry_msgs/Vector3", VECTOR3),
            ("geometry_msgs/Quaternion", QUATERNION),
        ],
    )
}

/// `nav_msgs/msg/OccupancyGrid`.
pub fn occupancy_grid() -> Schema {
    with_deps(
        "nav_msgs/msg/OccupancyGrid",
        OCCUPANCY_GRID,
        &[
            ("std_msgs/Header", HEADER),
            ("builtin_interfaces/Time", TIME),
            ("nav_msgs/MapMetaData", MAP_META),
            ("geometry_msgs/Pose", POSE),
            ("geometry_msgs/Point", POINT),
            ("geometry_msgs/Quaternion", QUATERNION),
        ],
    )
}

/// `visualization_msgs/msg/MarkerArray`.
pub fn marker_array() -> Schema {
    with_deps(
        "visualization_msgs/msg/MarkerArray",
        MARKER_ARRAY,
        &[
            ("visualization_msgs/Marker", MARKER),
            ("std_msgs/Header", HEADER),
            ("builtin_interfaces/Time", TIME),
            ("geometry_msgs/Pose", POSE),
            ("geometry_msgs/Point", POINT),
            ("geometry_msgs/Quaternion", QUATERNION),
            ("geometry_msgs/Vector3", VECTOR3),
            ("std_msgs/ColorRGBA", COLOR),
            ("builtin_interfaces/Duration", DURATION),
            ("sensor_msgs/CompressedImage", COMPRESSED_IMAGE),
            ("visualization_msgs/UVCoordinate", UV),
            ("visualization_msgs/MeshFile", MESH_FILE),
        ],
    )
}

/// `std_msgs/msg/String`.
pub fn string() -> Schema {
    with_deps("std_msgs/msg/String", STRING, &[])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dependencies_follow_separator_lines() {
        let s = laser_scan();
        let parts: Vec<&str> = s.text.split(&format!("{}\n", "=".repeat(80))).collect();
        assert_eq!(parts.len(), 3);
        assert!(parts[0].starts_with("std_msgs/Header header\n"));
        assert_eq!(
            parts[1],
            "MSG: std_msgs/Header\nbuiltin_interfaces/Time stamp\nstring frame_id\n"
        );
        assert_eq!(
            parts[2],
            "MSG: builtin_interfaces/Time\nint32 sec\nuint32 nanosec\n"
        );
        // Every type a definition names is defined in it.
        for s in [odometry(), tf_message(), occupancy_grid(), marker_array()] {
            for line in s.text.lines() {
                let Some(ty) = line.split_whitespace().next() else {
                    continue;
                };
                let base = ty.trim_end_matches("[]").split('[').next().unwrap();
                if base.contains('/') {
                    assert!(
                        s.text.contains(&format!("MSG: {base}\n")),
                        "{} lacks {base}",
                        s.name
                    );
                }
            }
        }
    }
}
