//! The one way the project writes a file (docs/cli.md#writes "Writes"): whole or not
//! at all. Used by every writer — the command-line tool (`-o`, `--report`,
//! `render -o`, `run --out`, `learn -o`, `--emit`, `ask`), the studio's
//! storage and [`crate::render::render_to_path`].
//!
//! [`atomic_write`] writes a temporary file in the target's folder, flushes
//! it to disk, then renames it over the target; a failure (a full disk, a
//! killed process) leaves the previous file as it was and removes the
//! temporary file. It refuses to replace an existing file that the user
//! could not write in place (no write permission bit, or not a regular
//! file where a rename would be wrong: a directory). Special files that
//! cannot be renamed over (`/dev/null`, a FIFO) are written in place.

use std::fs;
use std::io::{self, Write as _};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

static TMP_COUNTER: AtomicU64 = AtomicU64::new(0);

/// The temporary files [`atomic_write`] is writing now, for
/// [`remove_in_flight`].
static IN_FLIGHT: std::sync::Mutex<Vec<PathBuf>> = std::sync::Mutex::new(Vec::new());

fn in_flight() -> std::sync::MutexGuard<'static, Vec<PathBuf>> {
    IN_FLIGHT.lock().unwrap_or_else(|e| e.into_inner())
}

/// Remove the temporary files of the [`atomic_write`]s going on now (for a
/// signal handler that is about to end the process: SIGTERM, SIGHUP,
/// Ctrl-C). The targets keep their previous contents. Errors are ignored.
pub fn remove_in_flight() {
    for p in in_flight().drain(..) {
        let _ = fs::remove_file(p);
    }
}

/// The name prefix shared by every temporary file of [`atomic_write`]:
/// `.NAME.tmp-PID-N` beside the target `NAME`.
pub(crate) fn temp_name(target_name: &str, n: u64) -> String {
    format!(".{target_name}.tmp-{}-{n}", std::process::id())
}

/// Write `contents` to `path` atomically (see the module documentation).
pub fn atomic_write(path: &Path, contents: impl AsRef<[u8]>) -> io::Result<()> {
    let contents = contents.as_ref();
    // Follow a symbolic link: replace the file it points to, keep the link.
    let path: PathBuf = match fs::symlink_metadata(path) {
        Ok(m) if m.file_type().is_symlink() => fs::canonicalize(path).unwrap_or(path.into()),
        _ => path.to_path_buf(),
    };
    let mut permissions = None;
    match fs::metadata(&path) {
        Ok(m) if m.is_dir() => {
            return Err(io::Error::new(
                io::ErrorKind::IsADirectory,
                "is a directory; expected a file name",
            ))
        }
        Ok(m) if !m.is_file() => {
            // A device or a FIFO (`-o /dev/null`): renaming over it would
            // replace the device node itself; write to it as it is.
            let mut f = fs::OpenOptions::new().write(true).open(&path)?;
            f.write_all(contents)?;
            return f.flush();
        }
        Ok(m) if m.permissions().readonly() => {
            return Err(io::Error::new(
                io::ErrorKind::PermissionDenied,
                "the file is read-only; not replaced",
            ))
        }
        Ok(m) => permissions = Some(m.permissions()),
        Err(e) if e.kind() == io::ErrorKind::NotFound => {}
        Err(e) => return Err(e),
    }
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let n = TMP_COUNTER.fetch_add(1, Ordering::Relaxed);
    let tmp = dir.join(temp_name(&name, n));
    in_flight().push(tmp.clone());
    let result = (|| {
        let mut f = fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&tmp)?;
        f.write_all(contents)?;
        f.sync_all()?;
        if let Some(p) = permissions {
            // The replacement keeps the permissions of the file it replaces.
            let _ = f.set_permissions(p);
        }
        drop(f);
        fs::rename(&tmp, &path)?;
        // Make the rename itself durable.
        if let Ok(d) = fs::File::open(dir) {
            let _ = d.sync_all();
        }
        Ok(())
    })();
    if result.is_err() {
        let _ = fs::remove_file(&tmp);
    }
    in_flight().retain(|p| p != &tmp);
    result
}

/// The lock file of a task folder, shared by `rccpack ask` and the studio.
pub const LOCK_FILE: &str = ".rccpack.lock";

/// An exclusive lock on a task folder (`flock` on [`LOCK_FILE`] inside it):
/// `rccpack ask` holds it for its whole session and the studio while it
/// writes, so two sessions never interleave their writes (answers lost).
/// Released when dropped (or when the process ends, however it ends).
#[derive(Debug)]
pub struct DirLock {
    _file: fs::File,
}

impl DirLock {
    /// Take the lock without waiting: `Ok(None)` when another process (or
    /// another handle in this one) holds it.
    pub fn try_lock(dir: &Path) -> io::Result<Option<DirLock>> {
        let file = fs::OpenOptions::new()
            .read(true)
            .write(true)
            .create(true)
            .truncate(false)
            .open(dir.join(LOCK_FILE))?;
        #[cfg(unix)]
        {
            use std::os::unix::io::AsRawFd;
            // SAFETY: flock on a file descriptor this function owns, open
            // for the duration of the call; no memory is shared.
            let r = unsafe { libc::flock(file.as_raw_fd(), libc::LOCK_EX | libc::LOCK_NB) };
            if r != 0 {
                let e = io::Error::last_os_error();
                return if e.kind() == io::ErrorKind::WouldBlock {
                    Ok(None)
                } else {
                    Err(e)
                };
            }
        }
        Ok(Some(DirLock { _file: file }))
    }
}

/// Bytes that are not UTF-8 text: where the first bad byte is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error("not UTF-8 text: invalid byte 0x{byte:02x} at byte offset {offset} (line {line}); expected a UTF-8 text file")]
pub struct NotUtf8 {
    /// The first byte that is not UTF-8.
    pub byte: u8,
    /// Its offset from the start.
    pub offset: usize,
    /// Its 1-based line.
    pub line: usize,
}

/// Text from the bytes of a file: UTF-8, a leading byte-order mark
/// dropped; invalid UTF-8 is an error naming the byte offset of the first
/// bad byte (and its line).
pub fn utf8_text(bytes: Vec<u8>) -> Result<String, NotUtf8> {
    match String::from_utf8(bytes) {
        Ok(mut s) => {
            if s.starts_with('\u{feff}') {
                s.drain(..'\u{feff}'.len_utf8());
            }
            Ok(s)
        }
        Err(e) => {
            let at = e.utf8_error().valid_up_to();
            let b = e.as_bytes();
            // `\n`, `\r\n` and a lone `\r` end a line (as everywhere else).
            let head = &b[..at];
            let line = head
                .iter()
                .enumerate()
                .filter(|&(i, &c)| c == b'\n' || (c == b'\r' && b.get(i + 1) != Some(&b'\n')))
                .count()
                + 1;
            Err(NotUtf8 {
                byte: b[at],
                offset: at,
                line,
            })
        }
    }
}

/// Remove the temporary files [`atomic_write`] of this process left in
/// `dir` (after an interrupted write, e.g. on Ctrl-C). Errors are ignored.
pub fn remove_own_temp_files(dir: &Path) {
    let tag = format!(".tmp-{}-", std::process::id());
    if let Ok(entries) = fs::read_dir(dir) {
        for e in entries.flatten() {
            let name = e.file_name();
            let name = name.to_string_lossy();
            if name.starts_with('.') && name.contains(&tag) {
                let _ = fs::remove_file(e.path());
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tmpdir(tag: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("rccpack-fsutil-{tag}-{}", std::process::id()));
        let _ = fs::remove_dir_all(&d);
        fs::create_dir_all(&d).unwrap();
        d
    }

    #[test]
    fn writes_replaces_and_leaves_no_temp_file() {
        let d = tmpdir("basic");
        let p = d.join("a.json");
        atomic_write(&p, "one").unwrap();
        atomic_write(&p, "two").unwrap();
        assert_eq!(fs::read_to_string(&p).unwrap(), "two");
        assert_eq!(fs::read_dir(&d).unwrap().count(), 1);
    }

    #[test]
    fn refuses_read_only_file_and_directory() {
        let d = tmpdir("ro");
        let p = d.join("ro.txt");
        fs::write(&p, "keep").unwrap();
        let mut perm = fs::metadata(&p).unwrap().permissions();
        perm.set_readonly(true);
        fs::set_permissions(&p, perm).unwrap();
        let e = atomic_write(&p, "new").unwrap_err();
        assert!(e.to_string().contains("read-only"), "{e}");
        assert_eq!(fs::read_to_string(&p).unwrap(), "keep");
        let e = atomic_write(&d, "new").unwrap_err();
        assert!(e.to_string().contains("directory"), "{e}");
    }

    #[cfg(unix)]
    #[test]
    fn a_folder_lock_is_exclusive() {
        let d = tmpdir("lock");
        let held = DirLock::try_lock(&d).unwrap().expect("free");
        assert!(DirLock::try_lock(&d).unwrap().is_none());
        drop(held);
        assert!(DirLock::try_lock(&d).unwrap().is_some());
    }

    #[test]
    fn utf8_with_bom_and_bad_bytes() {
        assert_eq!(utf8_text(b"\xef\xbb\xbfrule".to_vec()).unwrap(), "rule");
        let e = utf8_text(b"ab\ncd\xffe".to_vec()).unwrap_err();
        let want = NotUtf8 {
            byte: 0xff,
            offset: 5,
            line: 2,
        };
        assert_eq!(e, want);
        assert!(
            e.to_string().contains("0xff at byte offset 5 (line 2)"),
            "{e}"
        );
        // Old Mac line ends count as lines too.
        assert_eq!(utf8_text(b"a\rb\rc\xff".to_vec()).unwrap_err().line, 3);
        assert_eq!(utf8_text(b"a\r\nb\xff".to_vec()).unwrap_err().line, 2);
    }

    #[cfg(unix)]
    #[test]
    fn writes_devices_in_place() {
        atomic_write(Path::new("/dev/null"), "x").unwrap();
        assert!(Path::new("/dev/null").exists());
    }
}
