//! The page and its scripts, compiled into the binary: the viewer's own files (`web/`) and
//! three.js (`web/vendor/three`, copied from npm by `scripts/vendor-three.sh`). Only these
//! exact paths are served; nothing is ever read from the file system.

/// One served file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Asset {
    /// URL path, starting with `/`.
    pub path: &'static str,
    /// Media type.
    pub content_type: &'static str,
    /// Contents.
    pub bytes: &'static [u8],
}

const HTML: &str = "text/html; charset=utf-8";
const JS: &str = "text/javascript; charset=utf-8";
const CSS: &str = "text/css; charset=utf-8";
const TEXT: &str = "text/plain; charset=utf-8";

macro_rules! asset {
    ($path:literal, $file:literal, $ty:expr) => {
        Asset {
            path: $path,
            content_type: $ty,
            bytes: include_bytes!(concat!("../web/", $file)),
        }
    };
}

/// Every served file.
pub const ASSETS: &[Asset] = &[
    asset!("/", "index.html", HTML),
    asset!("/viewer.js", "viewer.js", JS),
    asset!("/building.js", "building.js", JS),
    asset!("/viewer.css", "viewer.css", CSS),
    asset!("/vendor/three/LICENSE", "vendor/three/LICENSE", TEXT),
    asset!(
        "/vendor/three/three.module.js",
        "vendor/three/three.module.js",
        JS
    ),
    asset!(
        "/vendor/three/three.core.js",
        "vendor/three/three.core.js",
        JS
    ),
    asset!(
        "/vendor/three/addons/loaders/GLTFLoader.js",
        "vendor/three/addons/loaders/GLTFLoader.js",
        JS
    ),
    asset!(
        "/vendor/three/addons/utils/BufferGeometryUtils.js",
        "vendor/three/addons/utils/BufferGeometryUtils.js",
        JS
    ),
    asset!(
        "/vendor/three/addons/utils/SkeletonUtils.js",
        "vendor/three/addons/utils/SkeletonUtils.js",
        JS
    ),
    asset!(
        "/vendor/three/addons/controls/OrbitControls.js",
        "vendor/three/addons/controls/OrbitControls.js",
        JS
    ),
    asset!(
        "/vendor/three/addons/webxr/VRButton.js",
        "vendor/three/addons/webxr/VRButton.js",
        JS
    ),
];

/// The asset at URL path `path` (exact match; `/index.html` is `/`).
pub fn asset(path: &str) -> Option<&'static Asset> {
    let path = if path == "/index.html" { "/" } else { path };
    ASSETS.iter().find(|a| a.path == path)
}
