//! The BCF zip archive with deterministic bytes: entries in the order added, deflated, every
//! one with the same modification time (the BCF's creation date, clamped to what zip can
//! hold, 1980-2107) and permissions 0644, no other metadata.

use std::io::{Cursor, Write};

use zip::write::SimpleFileOptions;
use zip::{CompressionMethod, DateTime, ZipWriter};

use crate::BcfError;

/// A zip archive being built in memory.
#[derive(Debug)]
pub struct Archive {
    zip: ZipWriter<Cursor<Vec<u8>>>,
    options: SimpleFileOptions,
}

impl Archive {
    /// An empty archive whose entries are dated `secs` (seconds since 1970, UTC).
    pub fn new(secs: i64) -> Archive {
        let options = SimpleFileOptions::default()
            .compression_method(CompressionMethod::Deflated)
            .last_modified_time(zip_time(secs))
            .unix_permissions(0o644);
        Archive {
            zip: ZipWriter::new(Cursor::new(Vec::new())),
            options,
        }
    }

    /// Adds an entry.
    pub fn add(&mut self, name: &str, bytes: &[u8]) -> Result<(), BcfError> {
        let err = |source| BcfError::Zip {
            name: name.to_string(),
            source,
        };
        self.zip.start_file(name, self.options).map_err(err)?;
        self.zip
            .write_all(bytes)
            .map_err(|e| err(zip::result::ZipError::Io(e)))
    }

    /// The archive's bytes.
    pub fn finish(self) -> Result<Vec<u8>, BcfError> {
        self.zip
            .finish()
            .map(Cursor::into_inner)
            .map_err(|source| BcfError::Zip {
                name: "(central directory)".into(),
                source,
            })
    }
}

/// `secs` as a zip date and time (UTC), clamped to 1980-01-01 .. 2107-12-31.
fn zip_time(secs: i64) -> DateTime {
    let iso = poinav_ifc::timestamp::iso8601_utc(secs);
    let n = |r: std::ops::Range<usize>| iso.get(r).and_then(|t| t.parse::<u16>().ok());
    let parsed = (|| {
        let year = n(0..4)?;
        if year < 1980 {
            return None;
        }
        if year > 2107 {
            return DateTime::from_date_and_time(2107, 12, 31, 23, 59, 58).ok();
        }
        DateTime::from_date_and_time(
            year,
            n(5..7)? as u8,
            n(8..10)? as u8,
            n(11..13)? as u8,
            n(14..16)? as u8,
            n(17..19)? as u8,
        )
        .ok()
    })();
    parsed.unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_same_entries_give_the_same_bytes() {
        let make = || {
            let mut a = Archive::new(1_795_314_600);
            a.add("bcf.version", b"<Version/>").unwrap();
            a.add("x/markup.bcf", b"<Markup/>").unwrap();
            a.finish().unwrap()
        };
        let bytes = make();
        assert_eq!(bytes, make());
        assert_eq!(&bytes[..4], b"PK\x03\x04");
        let t = zip_time(1_795_314_600);
        assert_eq!(
            (t.year(), t.month(), t.day(), t.hour(), t.minute()),
            (2026, 11, 22, 2, 30)
        );
        assert_eq!(zip_time(0), DateTime::default());
    }
}
