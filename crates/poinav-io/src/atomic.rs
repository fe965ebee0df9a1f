//! Atomic output: write to a temporary file beside the target, then rename over it, so a
//! failed or interrupted write never leaves a partial file. Temporary files are named
//! `.poinav-<pid>-<random>.tmp`; one left behind by a process that was killed (SIGKILL cannot be
//! caught) is removed by the next write into the same folder once that process is gone.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;

/// Writes `bytes` to `path` atomically (temporary file in the same folder, synced, renamed).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    write_atomic_with(path, |w| w.write_all(bytes))
}

/// Like [`write_atomic`], for output produced piece by piece: `write` streams it into a
/// buffered writer on the temporary file, which becomes `path` only when `write` succeeds (an
/// error leaves `path` untouched and removes the temporary file).
pub fn write_atomic_with(
    path: &Path,
    write: impl FnOnce(&mut BufWriter<&File>) -> std::io::Result<()>,
) -> std::io::Result<()> {
    let tmp = temporary_beside(path)?;
    {
        let mut w = BufWriter::with_capacity(1 << 16, tmp.as_file());
        write(&mut w)?;
        w.flush()?;
    }
    tmp.as_file().sync_all()?;
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        tmp.as_file()
            .set_permissions(std::fs::Permissions::from_mode(0o644))?;
    }
    tmp.persist(path).map_err(|e| e.error)?;
    Ok(())
}

/// A new temporary file `.poinav-<pid>-<random>.tmp` in `path`'s folder (which must exist),
/// after sweeping the ones dead processes left there.
pub(crate) fn temporary_beside(path: &Path) -> std::io::Result<tempfile::NamedTempFile> {
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    sweep_stale(dir);
    tempfile::Builder::new()
        .prefix(&format!(".poinav-{}-", std::process::id()))
        .suffix(".tmp")
        .tempfile_in(dir)
}

/// The process id in a temporary file name `.poinav-<pid>-<random>.tmp`.
fn owner(name: &str) -> Option<u32> {
    let rest = name.strip_prefix(".poinav-")?.strip_suffix(".tmp")?;
    rest.split_once('-')?.0.parse().ok()
}

/// Removes temporary files in `dir` left by poinav processes that no longer run. Only where a
/// process's liveness can be told (`/proc`); failures are ignored (it is tidying, not output).
fn sweep_stale(dir: &Path) {
    let proc_fs = Path::new("/proc/self");
    if !proc_fs.exists() {
        return;
    }
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    let me = std::process::id();
    for e in entries.flatten() {
        let name = e.file_name();
        let Some(pid) = name.to_str().and_then(owner) else {
            continue;
        };
        if pid != me && !Path::new(&format!("/proc/{pid}")).exists() {
            let _ = std::fs::remove_file(e.path());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn writes_whole_files_and_leaves_no_temporary_on_failure() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("out.ifc");
        write_atomic(&target, b"abc").unwrap();
        write_atomic(&target, b"defg").unwrap();
        assert_eq!(std::fs::read(&target).unwrap(), b"defg");
        let missing = dir.path().join("no/such/dir/out.ifc");
        assert!(write_atomic(&missing, b"x").is_err());
        let names: Vec<_> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names, vec![std::ffi::OsString::from("out.ifc")]);
    }

    #[test]
    fn a_failed_streamed_write_leaves_the_target_untouched() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("out.glb");
        write_atomic_with(&target, |w| {
            w.write_all(b"head")?;
            w.write_all(&[7; 100_000])
        })
        .unwrap();
        assert_eq!(std::fs::metadata(&target).unwrap().len(), 100_004);
        let err = write_atomic_with(&target, |w| {
            w.write_all(b"partial")?;
            Err(std::io::Error::other("disk on fire"))
        })
        .unwrap_err();
        assert_eq!(err.to_string(), "disk on fire");
        assert_eq!(std::fs::metadata(&target).unwrap().len(), 100_004);
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }

    #[test]
    fn temporaries_of_dead_processes_are_swept_and_others_kept() {
        let dir = tempfile::tempdir().unwrap();
        // No process has this id (above Linux's largest pid, 2^22).
        let dead = ".poinav-99999999-abc123.tmp";
        // Process 1 always runs; our own temporaries may be in use.
        let alive = ".poinav-1-abc123.tmp";
        let mine = format!(".poinav-{}-abc123.tmp", std::process::id());
        let other = "notes.tmp";
        for n in [dead, alive, mine.as_str(), other] {
            std::fs::write(dir.path().join(n), b"x").unwrap();
        }
        write_atomic(&dir.path().join("out.ifc"), b"abc").unwrap();
        let mut names: Vec<String> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .collect();
        names.sort();
        let mut want = vec![
            alive.to_string(),
            mine,
            other.to_string(),
            "out.ifc".to_string(),
        ];
        if !Path::new("/proc/self").exists() {
            want.push(dead.to_string());
        }
        want.sort();
        assert_eq!(names, want);
        assert_eq!(owner(".poinav-42-x.tmp"), Some(42));
        assert_eq!(owner(".poinav-x.tmp"), None);
        assert_eq!(owner("poinav-42-x.tmp"), None);
    }
}
