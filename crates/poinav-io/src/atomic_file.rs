//! A file written as it is produced and published atomically: the bytes go to a temporary file
//! beside the target (made by [`crate::atomic`]: `.poinav-<pid>-<random>.tmp`, so a later
//! write sweeps one left by a killed process), which is synced and renamed over the
//! target by [`AtomicFile::commit`]; dropped without a commit, it is removed. A long trace is
//! streamed to disk this way without ever being held in memory, and a reader never sees half.

use std::io::{BufWriter, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};

use tempfile::NamedTempFile;

/// A buffered file under construction.
#[derive(Debug)]
pub struct AtomicFile {
    out: BufWriter<NamedTempFile>,
    path: PathBuf,
}

impl AtomicFile {
    /// Starts writing what will become `path` (its folder must exist).
    pub fn create(path: &Path) -> std::io::Result<AtomicFile> {
        let tmp = crate::atomic::temporary_beside(path)?;
        Ok(AtomicFile {
            out: BufWriter::with_capacity(1 << 20, tmp),
            path: path.to_path_buf(),
        })
    }

    /// The target path.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Flushes, syncs and renames the file over its target.
    pub fn commit(self) -> std::io::Result<()> {
        let tmp = self.out.into_inner().map_err(|e| e.into_error())?;
        tmp.as_file().sync_all()?;
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            tmp.as_file()
                .set_permissions(std::fs::Permissions::from_mode(0o644))?;
        }
        tmp.persist(&self.path).map_err(|e| e.error)?;
        Ok(())
    }
}

impl Write for AtomicFile {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.out.write(buf)
    }

    fn write_all(&mut self, buf: &[u8]) -> std::io::Result<()> {
        self.out.write_all(buf)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.out.flush()
    }
}

/// Seeking flushes the buffer first (`BufWriter`'s rule), so writers that patch a header or
/// an index afterwards (MCAP's summary offsets) work on the temporary file as on any file.
impl Seek for AtomicFile {
    fn seek(&mut self, pos: SeekFrom) -> std::io::Result<u64> {
        self.out.seek(pos)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nothing_appears_before_the_commit_and_a_drop_leaves_nothing() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("trace.jsonl");
        let mut f = AtomicFile::create(&target).unwrap();
        f.write_all(b"line 1\n").unwrap();
        assert!(!target.exists());
        f.write_all(b"line 2\n").unwrap();
        f.commit().unwrap();
        assert_eq!(std::fs::read(&target).unwrap(), b"line 1\nline 2\n");
        let mut g = AtomicFile::create(&target).unwrap();
        g.write_all(b"half").unwrap();
        drop(g);
        assert_eq!(std::fs::read(&target).unwrap(), b"line 1\nline 2\n");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }

    #[test]
    fn a_seek_back_patches_what_was_written() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("run.mcap");
        let mut f = AtomicFile::create(&target).unwrap();
        f.write_all(b"0000body").unwrap();
        assert_eq!(f.stream_position().unwrap(), 8);
        f.seek(SeekFrom::Start(0)).unwrap();
        f.write_all(b"HEAD").unwrap();
        f.seek(SeekFrom::End(0)).unwrap();
        f.write_all(b"!").unwrap();
        f.commit().unwrap();
        assert_eq!(std::fs::read(&target).unwrap(), b"HEADbody!");
    }
}
