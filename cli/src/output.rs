//! Outputs that lose nothing (what each failure leaves: `docs/reliability.md`).
//!
//! A file is written to a temporary file beside its destination (same directory, so the
//! same file system) and renamed over it only when complete ([`Output::commit`]). A run
//! that fails, is refused or is stopped drops its temporary files and leaves the
//! destination as it was; it never removes a path it did not create.
//!
//! A sequence of frames in a directory ([`Sequence`]) is written into a hidden temporary
//! directory inside the destination; at commit the new frames are renamed into place and
//! the earlier frames of the same name pattern that the new sequence does not have are
//! removed, so the directory holds exactly the new sequence, never a mix.
//!
//! **Devices and FIFOs.** A destination under `/dev` or `/proc` (`/dev/stdout`,
//! `/dev/null`), or one that exists and is neither a regular file nor a directory (a
//! character device, a FIFO, a socket), is written in place, as a stream: there is no
//! earlier content to keep, nothing is renamed over it and it is never removed. A run that
//! fails there may have written part of its output to the stream.
//!
//! Every temporary path is listed in [`PENDING`] while it exists. A signal that stops the
//! run at once ([`crate::interrupt`]) takes the list's lock, removes what it lists and
//! exits with the lock held; creating, committing and dropping take the same lock, so a
//! signal never finds a half-renamed sequence or misses a temporary file.

use crate::args::CliResult;
use std::fs::File;
use std::io;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard};

/// The temporary files and directories this run created and has not yet moved into place.
static PENDING: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

fn pending() -> MutexGuard<'static, Vec<PathBuf>> {
    PENDING.lock().unwrap_or_else(|e| e.into_inner())
}

fn forget(list: &mut Vec<PathBuf>, path: &Path) {
    list.retain(|p| p != path);
}

/// Removes every temporary path of this run and returns the lock on their list, which the
/// caller keeps until the process exits: nothing can be created or committed after it.
#[cfg_attr(target_family = "wasm", allow(dead_code))]
pub fn abandon_all() -> MutexGuard<'static, Vec<PathBuf>> {
    let list = pending();
    for path in list.iter() {
        let _ = if path.is_dir() {
            std::fs::remove_dir_all(path)
        } else {
            std::fs::remove_file(path)
        };
    }
    list
}

/// "cannot write PATH: ERROR", as an I/O error of the same kind.
pub fn named(path: &Path, e: io::Error) -> io::Error {
    io::Error::new(e.kind(), format!("cannot write {}: {e}", path.display()))
}

/// Refuses an empty path (`--out ""`), naming the flag.
pub fn non_empty(path: &Path, flag: &str) -> CliResult<()> {
    if path.as_os_str().is_empty() {
        Err(format!("{flag}: the path is empty; give a file name"))
    } else {
        Ok(())
    }
}

/// True for a destination written in place as a stream (see the module docs).
pub fn is_stream(path: &Path) -> bool {
    let special = path.starts_with("/dev") || path.starts_with("/proc");
    special || std::fs::metadata(path).is_ok_and(|m| !m.is_file() && !m.is_dir())
}

/// Where a path leads: its directory made absolute and symbolic links followed, and its
/// file name; two paths with the same identity are the same file.
fn identity(path: &Path) -> Option<PathBuf> {
    if let Ok(p) = std::fs::canonicalize(path) {
        return Some(p);
    }
    let path = through_links(path).ok()?;
    let parent = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    Some(std::fs::canonicalize(parent).ok()?.join(path.file_name()?))
}

/// Where `path` leads when it is a symbolic link whose target does not exist yet: the
/// target, followed link by link (a relative target from its link's directory), at most 40
/// links as the system follows. A path that is not a link is returned as it is.
fn through_links(path: &Path) -> io::Result<PathBuf> {
    let mut p = path.to_path_buf();
    for _ in 0..40 {
        match std::fs::symlink_metadata(&p) {
            Ok(m) if m.file_type().is_symlink() => {
                p = directory_of(&p).join(std::fs::read_link(&p)?);
            }
            _ => return Ok(p),
        }
    }
    Err(io::Error::other("too many levels of symbolic links"))
}

/// Refuses two flags that name the same file (devices and FIFOs excepted: a stream may
/// take several outputs).
pub fn distinct(paths: &[(&str, &Path)]) -> CliResult<()> {
    for (k, (flag_a, a)) in paths.iter().enumerate() {
        for (flag_b, b) in &paths[k + 1..] {
            if is_stream(a) || is_stream(b) {
                continue;
            }
            if a == b || (identity(a).is_some() && identity(a) == identity(b)) {
                return Err(format!(
                    "{flag_a} {} and {flag_b} {} name the same file; give each its own",
                    a.display(),
                    b.display()
                ));
            }
        }
    }
    Ok(())
}

/// One output file being written.
pub struct Output {
    /// The path as the user gave it (for messages).
    shown: PathBuf,
    /// Where the complete file goes (symbolic links followed).
    dest: PathBuf,
    /// The temporary file beside `dest`, or `None` for a stream.
    temp: Option<Temp>,
    /// The stream, for a device or FIFO.
    stream: Option<File>,
}

impl Output {
    /// Starts an output for `path` (named by `flag` in errors): a temporary file beside it,
    /// or the stream itself. Fails at once where the path cannot be written.
    pub fn create(path: &Path, flag: &str) -> CliResult<Self> {
        non_empty(path, flag)?;
        let fail = |e: io::Error| format!("cannot write {}: {e}", path.display());
        if is_stream(path) {
            let stream = std::fs::OpenOptions::new()
                .write(true)
                .open(path)
                .map_err(fail)?;
            return Ok(Self {
                shown: path.to_path_buf(),
                dest: path.to_path_buf(),
                temp: None,
                stream: Some(stream),
            });
        }
        let existing = std::fs::metadata(path).ok();
        if existing.as_ref().is_some_and(|m| m.is_dir()) {
            return Err(format!(
                "{flag} {}: is a directory; give a file name",
                path.display()
            ));
        }
        // Through a symbolic link to the file it names, even one that does not exist yet
        // (the link stays a link).
        let dest = match std::fs::canonicalize(path) {
            Ok(dest) => dest,
            Err(_) => through_links(path).map_err(fail)?,
        };
        if dest != path && !directory_of(&dest).is_dir() {
            return Err(format!(
                "{flag} {}: a symbolic link to {}, whose directory does not exist; create \
                 it or change the link",
                path.display(),
                dest.display()
            ));
        }
        let temp = temporary_beside(&dest, existing.map(|m| m.permissions())).map_err(fail)?;
        Ok(Self {
            shown: path.to_path_buf(),
            dest,
            temp: Some(temp),
            stream: None,
        })
    }

    /// A scratch file beside `path` (or in the system's temporary directory for a stream),
    /// removed when dropped: never committed.
    pub fn scratch(path: &Path) -> io::Result<Self> {
        let dir = if is_stream(path) {
            std::env::temp_dir().join("springwater")
        } else {
            path.to_path_buf()
        };
        Ok(Self {
            shown: path.to_path_buf(),
            dest: dir.clone(),
            temp: Some(temporary_beside(&dir, None).map_err(|e| named(path, e))?),
            stream: None,
        })
    }

    /// The path as given.
    pub fn path(&self) -> &Path {
        &self.shown
    }

    /// A handle on the file being written (the temporary file, or the stream).
    pub fn file(&self) -> io::Result<File> {
        let (file, path) = match (&self.temp, &self.stream) {
            (Some(t), _) => (&t.file, t.path.as_path()),
            (None, Some(s)) => (s, self.dest.as_path()),
            (None, None) => unreachable!("an output is a temporary file or a stream"),
        };
        let reopen = || {
            // WASI cannot duplicate a handle: the same file opened again by its name.
            let write = std::fs::OpenOptions::new().write(true).open(path);
            let both = std::fs::OpenOptions::new()
                .read(true)
                .write(true)
                .open(path);
            both.or(write)
        };
        match file.try_clone() {
            Err(e) if e.kind() == io::ErrorKind::Unsupported => reopen(),
            other => other,
        }
    }

    /// Moves the complete file into place (a stream: nothing to do).
    pub fn commit(self) -> io::Result<()> {
        commit_all(vec![Pending::File(self)])
    }

    /// The rename, under [`PENDING`]'s lock.
    fn commit_locked(mut self, list: &mut Vec<PathBuf>) -> io::Result<()> {
        let Some(temp) = self.temp.take() else {
            return Ok(());
        };
        let path = temp.path.clone();
        let result = temp.file.sync_all().and_then(|()| temp.persist(&self.dest));
        forget(list, &path);
        result.map_err(|e| named(&self.shown, e))
    }
}

impl Drop for Output {
    fn drop(&mut self) {
        if let Some(temp) = self.temp.take() {
            let mut list = pending();
            let path = temp.path.clone();
            drop(temp); // removes the temporary file
            forget(&mut list, &path);
        }
    }
}

/// A temporary file of this run, removed when dropped unless moved into place.
struct Temp {
    path: PathBuf,
    file: File,
}

impl Temp {
    /// Renames the file over `dest`.
    fn persist(mut self, dest: &Path) -> io::Result<()> {
        std::fs::rename(&self.path, dest)?;
        self.path = PathBuf::new();
        Ok(())
    }
}

impl Drop for Temp {
    fn drop(&mut self) {
        if !self.path.as_os_str().is_empty() {
            let _ = std::fs::remove_file(&self.path);
        }
    }
}

/// The directory a file of `dest` goes in.
fn directory_of(dest: &Path) -> &Path {
    match dest.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

/// A temporary file beside `dest`, listed in [`PENDING`]; with `permissions` (those of the
/// file it will replace) or, for a new file, the mode a created file gets (0666 less the
/// umask, on Unix).
fn temporary_beside(dest: &Path, permissions: Option<std::fs::Permissions>) -> io::Result<Temp> {
    let name = dest.file_name().unwrap_or_default().to_string_lossy();
    let prefix = format!(".{}.", shortened(&name));
    let mut list = pending();
    let (file, path) = unique_in(directory_of(dest), &prefix, ".springwater-tmp", |path| {
        std::fs::OpenOptions::new()
            .read(true)
            .write(true)
            .create_new(true)
            .open(path)
    })?;
    let temp = Temp { path, file };
    // A replaced file keeps its mode (WASI has no modes).
    #[cfg(unix)]
    if let Some(p) = permissions {
        temp.file.set_permissions(p)?;
    }
    #[cfg(not(unix))]
    drop(permissions);
    list.push(temp.path.clone());
    Ok(temp)
}

/// The most bytes of a destination's name that a temporary name repeats: with the dot
/// before it, the dot and six random characters after it and `.springwater-tmp`, the
/// temporary name stays within the 255 bytes a file name may have (so a destination whose
/// own name is that long can still be written).
const NAME_IN_TEMP: usize = 200;

/// `name`, cut to at most [`NAME_IN_TEMP`] bytes on a character boundary.
fn shortened(name: &str) -> &str {
    let mut end = name.len().min(NAME_IN_TEMP);
    while !name.is_char_boundary(end) {
        end -= 1;
    }
    &name[..end]
}

/// A new file or directory in `dir` named `PREFIX` + random characters + `SUFFIX`, made by
/// `tempfile` (0666 or 0777 less the umask on Unix).
#[cfg(not(target_family = "wasm"))]
fn unique_in<T>(
    dir: &Path,
    prefix: &str,
    suffix: &str,
    _create: impl Fn(&Path) -> io::Result<T>,
) -> io::Result<(T, PathBuf)>
where
    T: FromTemp,
{
    T::make(dir, prefix, suffix)
}

/// What [`unique_in`] makes with `tempfile`: a file or a directory.
#[cfg(not(target_family = "wasm"))]
trait FromTemp: Sized {
    fn make(dir: &Path, prefix: &str, suffix: &str) -> io::Result<(Self, PathBuf)>;
}

#[cfg(not(target_family = "wasm"))]
fn builder<'a>(prefix: &'a str, suffix: &'a str, mode: u32) -> tempfile::Builder<'a, 'a> {
    let mut b = tempfile::Builder::new();
    b.prefix(prefix).suffix(suffix);
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        b.permissions(std::fs::Permissions::from_mode(mode));
    }
    #[cfg(not(unix))]
    let _ = mode;
    b
}

/// `tempfile`'s error without the temporary path it names (the user never chose it and
/// never sees the file): the system's error alone.
#[cfg(not(target_family = "wasm"))]
fn without_path(e: io::Error) -> io::Error {
    // `tempfile` adds ` at path "…"` to the system's message.
    let text = e.to_string();
    match text.split_once(" at path \"") {
        Some((system, _)) => io::Error::new(e.kind(), system),
        None => e,
    }
}

#[cfg(not(target_family = "wasm"))]
impl FromTemp for File {
    fn make(dir: &Path, prefix: &str, suffix: &str) -> io::Result<(Self, PathBuf)> {
        let temp = builder(prefix, suffix, 0o666)
            .tempfile_in(dir)
            .map_err(without_path)?;
        // Removed or renamed by this module, not by `NamedTempFile`.
        temp.keep().map_err(|e| e.error)
    }
}

#[cfg(not(target_family = "wasm"))]
impl FromTemp for () {
    fn make(dir: &Path, prefix: &str, suffix: &str) -> io::Result<(Self, PathBuf)> {
        let temp = builder(prefix, suffix, 0o777)
            .tempdir_in(dir)
            .map_err(without_path)?;
        Ok(((), temp.keep()))
    }
}

/// WASI: `tempfile` makes a relative directory absolute with the emulated current
/// directory, which is not the one the host maps `.` to; names are tried here instead.
#[cfg(target_family = "wasm")]
fn unique_in<T>(
    dir: &Path,
    prefix: &str,
    suffix: &str,
    create: impl Fn(&Path) -> io::Result<T>,
) -> io::Result<(T, PathBuf)> {
    use std::hash::{BuildHasher, Hasher};
    let mut hasher = std::collections::hash_map::RandomState::new().build_hasher();
    for attempt in 0u32..1000 {
        hasher.write_u32(attempt);
        let path = dir.join(format!("{prefix}{:08x}{suffix}", hasher.finish() as u32));
        match create(&path) {
            Ok(made) => return Ok((made, path)),
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists => continue,
            Err(e) => return Err(e),
        }
    }
    Err(io::Error::new(
        io::ErrorKind::AlreadyExists,
        "no free temporary name",
    ))
}

/// A sequence of numbered frames (`PREFIX0001.EXT` …) being written into a directory.
pub struct Sequence {
    shown: PathBuf,
    dest: PathBuf,
    /// The hidden directory inside `dest` that holds the new frames until commit.
    temp: PathBuf,
    /// The destination (or an ancestor) when this run created it, removed on failure.
    created: Option<PathBuf>,
    prefix: &'static str,
    ext: &'static str,
    /// Digits in a frame number: 4, or more for sequences past 9,999 (names sort in order).
    digits: usize,
}

impl Sequence {
    /// Starts a sequence in `dir` whose largest frame number is `last`.
    pub fn create(
        dir: &Path,
        flag: &str,
        prefix: &'static str,
        ext: &'static str,
        last: usize,
    ) -> CliResult<Self> {
        non_empty(dir, flag)?;
        let fail = |e: io::Error| format!("cannot create {}: {e}", dir.display());
        if dir.exists() && !dir.is_dir() {
            return Err(format!(
                "{flag} {}: exists and is not a directory",
                dir.display()
            ));
        }
        let mut list = pending();
        let created = dir
            .ancestors()
            .take_while(|a| !a.as_os_str().is_empty() && !a.exists())
            .last()
            .map(Path::to_path_buf);
        std::fs::create_dir_all(dir).map_err(fail)?;
        // Absolute where the system can say (WASI cannot: the path as given serves).
        let absolute = |p: &Path| std::fs::canonicalize(p).unwrap_or_else(|_| p.to_path_buf());
        let dest = absolute(dir);
        let created = created.map(|c| absolute(&c));
        if let Some(c) = &created {
            list.push(c.clone());
        }
        let temp = match unique_in(&dest, ".springwater-tmp-", "", |p| std::fs::create_dir(p)) {
            Ok(((), path)) => path,
            Err(e) => {
                drop(list);
                remove_created(&created);
                return Err(fail(e));
            }
        };
        list.push(temp.clone());
        Ok(Self {
            shown: dir.to_path_buf(),
            dest,
            temp,
            created,
            prefix,
            ext,
            digits: last.to_string().len().max(4),
        })
    }

    /// The file name of frame `k`.
    pub fn name(&self, k: usize) -> String {
        format!("{}{k:0w$}.{}", self.prefix, self.ext, w = self.digits)
    }

    /// Where frame `k` is written until commit.
    pub fn frame_path(&self, k: usize) -> PathBuf {
        self.temp.join(self.name(k))
    }

    /// The directory as given.
    pub fn path(&self) -> &Path {
        &self.shown
    }

    /// True for a name of this sequence's pattern (any number of digits).
    fn is_frame(&self, name: &str) -> bool {
        name.strip_prefix(self.prefix)
            .and_then(|rest| rest.strip_suffix(self.ext))
            .and_then(|rest| rest.strip_suffix('.'))
            .is_some_and(|digits| !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit()))
    }

    fn commit_locked(mut self, list: &mut Vec<PathBuf>) -> io::Result<()> {
        let moved = self.move_frames();
        if moved.is_err() {
            let _ = std::fs::remove_dir_all(&self.temp);
        }
        forget(list, &self.temp);
        if let Some(c) = self.created.take() {
            forget(list, &c);
        }
        // Done: dropping `self` (with the lock held by the caller) has nothing left to do.
        self.temp = PathBuf::new();
        moved
    }

    /// Renames the new frames into place, then removes the earlier sequence's frames that
    /// the new one does not have, and the emptied temporary directory.
    fn move_frames(&self) -> io::Result<()> {
        let fail = |e: io::Error| named(&self.shown, e);
        let mut new = Vec::new();
        for entry in std::fs::read_dir(&self.temp).map_err(fail)? {
            new.push(entry.map_err(fail)?.file_name());
        }
        for name in &new {
            std::fs::rename(self.temp.join(name), self.dest.join(name)).map_err(fail)?;
        }
        for entry in std::fs::read_dir(&self.dest).map_err(fail)? {
            let name = entry.map_err(fail)?.file_name();
            if self.is_frame(&name.to_string_lossy()) && !new.contains(&name) {
                std::fs::remove_file(self.dest.join(&name)).map_err(fail)?;
            }
        }
        std::fs::remove_dir(&self.temp).map_err(fail)
    }
}

/// Removes the directories a failed sequence created.
fn remove_created(created: &Option<PathBuf>) {
    if let Some(c) = created {
        let _ = std::fs::remove_dir_all(c);
    }
}

impl Drop for Sequence {
    fn drop(&mut self) {
        if self.temp.as_os_str().is_empty() {
            return;
        }
        let mut list = pending();
        let _ = std::fs::remove_dir_all(&self.temp);
        forget(&mut list, &self.temp);
        remove_created(&self.created);
        if let Some(c) = &self.created {
            forget(&mut list, c);
        }
    }
}

/// An output waiting to be moved into place.
pub enum Pending {
    File(Output),
    Frames(Sequence),
}

/// Moves every output into place, under one lock: a signal comes before or after all of
/// them, never between two.
pub fn commit_all(outputs: Vec<Pending>) -> io::Result<()> {
    let mut list = pending();
    let mut outputs = outputs.into_iter();
    let result = outputs.try_for_each(|output| match output {
        Pending::File(o) => o.commit_locked(&mut list),
        Pending::Frames(s) => s.commit_locked(&mut list),
    });
    // After a failure the rest are dropped (their temporary files removed) without the lock.
    drop(list);
    drop(outputs);
    result
}
