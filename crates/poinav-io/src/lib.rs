//! Writing output files, shared by every crate that writes one: atomic file output
//! ([`atomic`]; [`atomic_file`] for output streamed as it is produced) and XML/HTML/SVG
//! escaping ([`xml`]), numbers as deterministic text ([`number`]: fixed decimals without
//! `-0` or trailing zeros), and IFC GlobalIds ([`global_id`]: the ids written into output, derived
//! from names so output is reproducible). Deliberately small and free of IFC (STEP) and geometry, so a crate that
//! only writes files does not pull in the STEP reader.

pub mod atomic;
pub mod atomic_file;
pub mod global_id;
pub mod number;
pub mod xml;

pub use atomic::{write_atomic, write_atomic_with};
pub use atomic_file::AtomicFile;
pub use global_id::{GlobalId, GlobalIdError};
