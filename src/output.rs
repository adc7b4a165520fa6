//! Where outputs go and how they get there.
//!
//! Every command that writes checks its destination before any computation ([`OutputDir::check`],
//! [`OutputFile::check`]): the location is a directory (or a regular file) or can be created,
//! it is writable, and its file system has room for the estimate. A directory of outputs is an
//! *output set*: it is written whole into a staging directory beside the destination (see
//! [`crate::staging`]), listed in a manifest (every file with its size and SHA-256), and moved into
//! place in one step — an atomic exchange with the previous set where the file system offers one —
//! so a reader sees the old set or the new one, never a mixture, and a failed or interrupted run
//! leaves the old set as it was. A single-file output is written beside its destination and renamed
//! into place. Only what shadowlab wrote is ever replaced: a regular file, an empty directory or a
//! directory with a shadowlab manifest; a symbolic link, device, FIFO, socket or foreign directory
//! where an output goes is refused, naming the flag.

use std::fs::File;
use std::io::Write;
use std::path::{Component, Path, PathBuf};

use anyhow::Context;
use rustix::fs::{Access, CWD, RenameFlags};
use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};

use crate::error::CliError;
use crate::staging;

/// The manifest of an output set: its own file, beside the set's other files.
pub(crate) const MANIFEST_NAME: &str = "manifest.json";

/// Free space kept beyond a run's estimate, for the manifest, directory entries and file-system
/// rounding.
const SPACE_MARGIN_BYTES: u64 = 1 << 20;

/// The longest name [`slug`] returns.
const MAX_SLUG_LENGTH: usize = 100;

/// A bound on the tables, reports, plots and manifest of one command's outputs, beside its
/// pictures, for the free-space check.
pub(crate) const TEXT_BOUND: u64 = 4 << 20;

/// The pictures of one pictured combination (eye view, difference image, its causes, heat map),
/// each written raw and annotated.
pub(crate) const PICTURES: u64 = shadowlab_analysis::pictures::PictureKind::ALL.len() as u64;

/// A bound on the bytes of a PNG of `width` × `height` pixels of `bytes_per_pixel` bytes: the raw
/// pixels, deflate's worst-case overhead (under 0.1 %) and the headers.
pub(crate) fn png_bound(width: u32, height: u32, bytes_per_pixel: u64) -> u64 {
    let raw = u64::from(width) * u64::from(height) * bytes_per_pixel;
    raw + raw / 1000 + 4096
}

/// A bound on the bytes of an annotated picture ([`shadowlab_plot::render_picture`], RGBA) of an
/// image of `width` × `height` pixels: the image framed by margins, at least 1200 pixels wide (room
/// for a long title), and up to 320 rows of title and key.
pub(crate) fn annotated_png_bound(width: u32, height: u32) -> u64 {
    png_bound(
        (width + 2 * shadowlab_plot::MARGIN).max(1200),
        height + 320,
        4,
    )
}

/// An output set's manifest: every file (by its path inside the set, `/`-separated), its size in
/// bytes and its SHA-256 in hex; the tool's version and the command that wrote it.
#[derive(Debug, Serialize, Deserialize)]
struct Manifest {
    shadowlab: String,
    command: String,
    files: Vec<ManifestEntry>,
}

/// One file of a [`Manifest`].
#[derive(Debug, Serialize, Deserialize)]
struct ManifestEntry {
    name: String,
    bytes: u64,
    sha256: String,
}

/// A name from a file, made safe to be one component of a path: ASCII letters, digits, `-`, `_`
/// and `.` are kept, any other run of characters becomes one `-`, leading dots and dashes are
/// dropped (no hidden files, no `..`), at most [`MAX_SLUG_LENGTH`] characters; `fallback` when
/// nothing is left.
pub(crate) fn slug(name: &str, fallback: &str) -> String {
    let mut out = String::new();
    for c in name.chars() {
        if c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.') {
            out.push(c);
        } else if !out.ends_with('-') {
            out.push('-');
        }
    }
    let trimmed = out
        .trim_start_matches(['.', '-'])
        .chars()
        .take(MAX_SLUG_LENGTH)
        .collect::<String>();
    let trimmed = trimmed.trim_end_matches('-');
    if trimmed.is_empty() {
        fallback.to_string()
    } else {
        trimmed.to_string()
    }
}

/// What kind of file system object `meta` describes, for messages.
fn kind(meta: &std::fs::Metadata) -> &'static str {
    use std::os::unix::fs::FileTypeExt;
    let t = meta.file_type();
    if t.is_symlink() {
        "a symbolic link"
    } else if t.is_dir() {
        "a directory"
    } else if t.is_char_device() {
        "a character device"
    } else if t.is_block_device() {
        "a block device"
    } else if t.is_fifo() {
        "a FIFO"
    } else if t.is_socket() {
        "a socket"
    } else {
        "a regular file"
    }
}

/// The absolute form of `path` (without resolving links) and its parent directory; refuses paths
/// whose last component is not a name (`.`, `..`, `/`).
fn absolute_with_parent(path: &Path, flag: &str) -> Result<(PathBuf, PathBuf), CliError> {
    let absolute = std::path::absolute(path)
        .with_context(|| format!("cannot resolve {flag} {}", path.display()))?;
    match (absolute.parent(), absolute.components().next_back()) {
        (Some(parent), Some(Component::Normal(_))) => {
            let parent = parent.to_path_buf();
            Ok((absolute, parent))
        }
        _ => Err(CliError::Input(format!(
            "invalid {flag}: {} does not end in a name; give a new or shadowlab-written location",
            path.display()
        ))),
    }
}

/// Whether a lookup failed because nothing is there (or a component on the way is not a
/// directory, which [`check_location`] then names).
fn is_absent(error: &std::io::Error) -> bool {
    matches!(
        error.kind(),
        std::io::ErrorKind::NotFound | std::io::ErrorKind::NotADirectory
    )
}

/// Checks that `parent` is, or can be created as, a writable directory with `needed` bytes free.
fn check_location(parent: &Path, flag: &str, needed: u64) -> Result<(), CliError> {
    let mut existing = parent;
    loop {
        match std::fs::metadata(existing) {
            Ok(meta) if meta.is_dir() => break,
            Ok(meta) => {
                return Err(CliError::Input(format!(
                    "invalid {flag}: {} is {}, not a directory",
                    existing.display(),
                    kind(&meta)
                )));
            }
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                existing = existing.parent().unwrap_or(Path::new("/"));
            }
            Err(e) => {
                return Err(CliError::Input(format!(
                    "invalid {flag}: cannot use {}: {e}",
                    existing.display()
                )));
            }
        }
    }
    rustix::fs::access(existing, Access::WRITE_OK | Access::EXEC_OK).map_err(|e| {
        CliError::Input(format!(
            "invalid {flag}: {} is not writable: {}",
            existing.display(),
            std::io::Error::from(e)
        ))
    })?;
    let stat = rustix::fs::statvfs(existing)
        .with_context(|| format!("cannot read the free space of {}", existing.display()))?;
    let free = stat.f_bavail.saturating_mul(stat.f_frsize);
    let needed = needed.saturating_add(SPACE_MARGIN_BYTES);
    if needed > free {
        return Err(CliError::Failure(anyhow::anyhow!(
            "not enough space for {flag}: the outputs need about {} MiB and {} has {} MiB free",
            needed.div_ceil(1 << 20),
            existing.display(),
            free >> 20
        )));
    }
    Ok(())
}

/// Whether the directory `dir` may be replaced as a whole: it is empty or holds a shadowlab
/// manifest.
fn is_replaceable(dir: &Path) -> std::io::Result<bool> {
    let mut entries = std::fs::read_dir(dir)?;
    if entries.next().is_none() {
        return Ok(true);
    }
    Ok(std::fs::read(dir.join(MANIFEST_NAME))
        .ok()
        .and_then(|bytes| serde_json::from_slice::<Manifest>(&bytes).ok())
        .is_some())
}

/// Flushes a directory's entries to disk (after a rename into it).
fn sync_directory(dir: &Path) -> Result<(), CliError> {
    File::open(dir)
        .and_then(|d| d.sync_all())
        .with_context(|| format!("cannot flush directory {}", dir.display()))?;
    Ok(())
}

/// Removes orphaned staging entries in `dir` and says so.
fn clear_orphans(dir: &Path) {
    for path in staging::remove_orphans(dir) {
        eprintln!(
            "shadowlab: removed {}, left by a run that did not finish",
            path.display()
        );
    }
}

/// A staging entry of this process: removed when dropped unless it has been moved away.
struct Staged {
    path: PathBuf,
}

impl Staged {
    fn new(path: PathBuf) -> Self {
        staging::remember(&path);
        Self { path }
    }
}

impl Drop for Staged {
    fn drop(&mut self) {
        // Best effort: what cannot be removed now, the next run removes as an orphan.
        let _ = staging::remove(&self.path);
        staging::forget(&self.path);
    }
}

/// Where an output goes: the path as the user gave it, its absolute form, its parent directory
/// (where staging happens) and the flag that named it.
#[derive(Debug)]
struct Destination {
    target: PathBuf,
    absolute: PathBuf,
    parent: PathBuf,
    flag: &'static str,
}

impl Destination {
    fn new(target: PathBuf, flag: &'static str) -> Result<Self, CliError> {
        let (absolute, parent) = absolute_with_parent(&target, flag)?;
        Ok(Self {
            target,
            absolute,
            parent,
            flag,
        })
    }

    /// Creates the parent directory if needed and removes the orphans of killed runs in it.
    fn open_parent(&self) -> Result<(), CliError> {
        std::fs::create_dir_all(&self.parent)
            .with_context(|| format!("cannot create directory {}", self.parent.display()))?;
        clear_orphans(&self.parent);
        Ok(())
    }
}

/// A directory that receives an output set, checked before the work that fills it.
#[derive(Debug)]
pub(crate) struct OutputDir {
    to: Destination,
}

impl OutputDir {
    /// Checks `target` (given by `flag`, or a default) before any work: not a link or a
    /// non-directory; if it exists, empty or an earlier shadowlab output set; its location
    /// writable with room for `estimate` bytes.
    pub(crate) fn check(
        target: PathBuf,
        flag: &'static str,
        estimate: u64,
    ) -> Result<Self, CliError> {
        let to = Destination::new(target, flag)?;
        let (target, absolute) = (&to.target, &to.absolute);
        match std::fs::symlink_metadata(absolute) {
            Ok(meta) if meta.is_dir() => {
                let replaceable = is_replaceable(absolute)
                    .with_context(|| format!("cannot read {flag} {}", target.display()))?;
                if !replaceable {
                    return Err(CliError::Input(format!(
                        "invalid {flag}: {} holds files that are not a shadowlab output set (no \
                         {MANIFEST_NAME}); choose an empty or new directory",
                        target.display()
                    )));
                }
            }
            Ok(meta) => {
                return Err(CliError::Input(format!(
                    "invalid {flag}: {} is {}; shadowlab writes an output set only to a new, an \
                     empty or a shadowlab-written directory",
                    target.display(),
                    kind(&meta)
                )));
            }
            Err(e) if is_absent(&e) => {}
            Err(e) => {
                return Err(CliError::Input(format!(
                    "invalid {flag}: cannot use {}: {e}",
                    target.display()
                )));
            }
        }
        check_location(&to.parent, flag, estimate)?;
        Ok(Self { to })
    }

    /// The directory as the user gave it.
    pub(crate) fn path(&self) -> &Path {
        &self.to.target
    }

    /// Writes `files` (paths relative to the set, `/`-separated) and their manifest as one set,
    /// replacing whatever set was there before as a whole.
    pub(crate) fn write(&self, command: &str, files: &[(String, Vec<u8>)]) -> Result<(), CliError> {
        let mut set = self.begin(command)?;
        for (name, bytes) in files {
            set.add(name, bytes)?;
        }
        set.finish()
    }

    /// Starts a set to be filled file by file ([`OutputSet::add`]) and put in place as a whole by
    /// [`OutputSet::finish`]; dropped unfinished, it leaves nothing behind.
    pub(crate) fn begin(&self, command: &str) -> Result<OutputSet<'_>, CliError> {
        self.to.open_parent()?;
        let staged = Staged::new(
            tempfile::Builder::new()
                .prefix(&staging::own_prefix())
                .permissions(std::os::unix::fs::PermissionsExt::from_mode(0o755))
                .tempdir_in(&self.to.parent)
                .with_context(|| {
                    format!(
                        "cannot create a staging directory in {}",
                        self.to.parent.display()
                    )
                })?
                .keep(),
        );
        Ok(OutputSet {
            dir: self,
            staged,
            manifest: Manifest {
                shadowlab: env!("CARGO_PKG_VERSION").to_string(),
                command: command.to_string(),
                files: Vec::new(),
            },
        })
    }

    /// Moves the staged set into place: a rename where nothing is, an atomic exchange where a
    /// set is (the previous set then sits at `staged`), and where the file system cannot exchange,
    /// two renames with the previous set moved aside first.
    fn publish(&self, staged: &Path) -> Result<(), CliError> {
        let moved = |e: rustix::io::Errno| {
            CliError::Failure(anyhow::Error::new(std::io::Error::from(e)).context(format!(
                "cannot move the finished output set to {} {}",
                self.to.flag,
                self.to.target.display()
            )))
        };
        loop {
            match rustix::fs::renameat_with(
                CWD,
                staged,
                CWD,
                &self.to.absolute,
                RenameFlags::NOREPLACE,
            ) {
                Ok(()) => return Ok(()),
                Err(rustix::io::Errno::EXIST | rustix::io::Errno::NOTEMPTY) => {}
                Err(e) => return Err(moved(e)),
            }
            // Something is there: it must still be a directory shadowlab may replace.
            let meta = std::fs::symlink_metadata(&self.to.absolute);
            match meta {
                Ok(meta) if meta.is_dir() && is_replaceable(&self.to.absolute).unwrap_or(false) => {
                }
                Ok(_) => {
                    return Err(CliError::Input(format!(
                        "invalid {}: {} was changed during the run and is no longer an output \
                         set shadowlab may replace",
                        self.to.flag,
                        self.to.target.display()
                    )));
                }
                // It went away since the rename was tried: try again.
                Err(_) => continue,
            }
            match rustix::fs::renameat_with(
                CWD,
                staged,
                CWD,
                &self.to.absolute,
                RenameFlags::EXCHANGE,
            ) {
                Ok(()) => return Ok(()),
                Err(rustix::io::Errno::NOENT) => continue,
                Err(rustix::io::Errno::INVAL | rustix::io::Errno::NOSYS) => {
                    // No exchange on this file system: move the old set aside, then the new
                    // one in. Between the two renames the destination is briefly absent.
                    let aside = staged.with_file_name(format!("{}old", staging::own_prefix()));
                    let aside = Staged::new(aside);
                    std::fs::rename(&self.to.absolute, &aside.path).with_context(|| {
                        format!(
                            "cannot move the previous set {} aside",
                            self.to.target.display()
                        )
                    })?;
                    std::fs::rename(staged, &self.to.absolute).with_context(|| {
                        format!(
                            "cannot move the finished output set to {}",
                            self.to.target.display()
                        )
                    })?;
                    return Ok(());
                }
                Err(e) => return Err(moved(e)),
            }
        }
    }
}

/// An output set being staged: its files are written (and flushed) as they come, so a set larger
/// than memory can be written; [`Self::finish`] adds the manifest and moves the set into place.
pub(crate) struct OutputSet<'a> {
    dir: &'a OutputDir,
    staged: Staged,
    manifest: Manifest,
}

impl OutputSet<'_> {
    /// Writes one file of the set (`name` relative to it, `/`-separated).
    pub(crate) fn add(&mut self, name: &str, bytes: &[u8]) -> Result<(), CliError> {
        let relative = Path::new(name);
        let plain = relative
            .components()
            .all(|c| matches!(c, Component::Normal(_)));
        if !plain || name == MANIFEST_NAME || self.manifest.files.iter().any(|f| f.name == name) {
            return Err(CliError::Failure(anyhow::anyhow!(
                "internal error: output name {name:?} is not a new plain relative path"
            )));
        }
        let path = self.staged.path.join(relative);
        if let Some(dir) = path.parent() {
            std::fs::create_dir_all(dir)
                .with_context(|| format!("cannot create directory {}", dir.display()))?;
        }
        write_synced(&path, bytes, &self.dir.to.target.join(relative))?;
        self.manifest.files.push(ManifestEntry {
            name: name.to_string(),
            bytes: bytes.len() as u64,
            sha256: hex(&Sha256::digest(bytes)),
        });
        Ok(())
    }

    /// Adds the manifest and moves the set into place, replacing the set that was there.
    pub(crate) fn finish(mut self) -> Result<(), CliError> {
        self.manifest.files.sort_by(|a, b| a.name.cmp(&b.name));
        let json =
            serde_json::to_vec_pretty(&self.manifest).context("cannot encode the manifest")?;
        let target = &self.dir.to.target;
        write_synced(
            &self.staged.path.join(MANIFEST_NAME),
            &json,
            &target.join(MANIFEST_NAME),
        )?;
        sync_directory(&self.staged.path)?;
        self.dir.publish(&self.staged.path)?;
        sync_directory(&self.dir.to.parent)
        // `staged` now names the previous set (or nothing); dropping it removes that.
    }
}

/// A single output file, checked before the work that fills it.
#[derive(Debug)]
pub(crate) struct OutputFile {
    to: Destination,
}

impl OutputFile {
    /// Checks `target` (given by `flag`) before any work: absent or a regular file, its
    /// directory writable (or creatable) with room for `estimate` bytes.
    pub(crate) fn check(
        target: PathBuf,
        flag: &'static str,
        estimate: u64,
    ) -> Result<Self, CliError> {
        let to = Destination::new(target, flag)?;
        check_replaceable_file(&to.absolute, &to.target, flag)?;
        check_location(&to.parent, flag, estimate)?;
        Ok(Self { to })
    }

    /// The file as the user gave it.
    pub(crate) fn path(&self) -> &Path {
        &self.to.target
    }

    /// Writes `bytes` beside the destination and renames the file into place.
    pub(crate) fn write(&self, bytes: &[u8]) -> Result<(), CliError> {
        self.to.open_parent()?;
        let temporary = tempfile::Builder::new()
            .prefix(&staging::own_prefix())
            .tempfile_in(&self.to.parent)
            .with_context(|| {
                format!(
                    "cannot create a temporary file in {}",
                    self.to.parent.display()
                )
            })?;
        let (_, path) = temporary
            .keep()
            .context("cannot keep the temporary output file")?;
        let staged = Staged::new(path);
        write_synced(&staged.path, bytes, &self.to.target)?;
        check_replaceable_file(&self.to.absolute, &self.to.target, self.to.flag)?;
        std::fs::rename(&staged.path, &self.to.absolute).with_context(|| {
            format!(
                "cannot move the finished file to {} {}",
                self.to.flag,
                self.to.target.display()
            )
        })?;
        sync_directory(&self.to.parent)
    }
}

/// Refuses anything but a regular file (or nothing) at `absolute`.
fn check_replaceable_file(absolute: &Path, target: &Path, flag: &str) -> Result<(), CliError> {
    match std::fs::symlink_metadata(absolute) {
        Ok(meta) if meta.is_file() => Ok(()),
        Ok(meta) if meta.is_dir() => Err(CliError::Input(format!(
            "invalid {flag}: {} is a directory; give a file name inside it",
            target.display()
        ))),
        Ok(meta) => Err(CliError::Input(format!(
            "invalid {flag}: {} is {}; shadowlab replaces only regular files",
            target.display(),
            kind(&meta)
        ))),
        Err(e) if is_absent(&e) => Ok(()),
        Err(e) => Err(CliError::Input(format!(
            "invalid {flag}: cannot use {}: {e}",
            target.display()
        ))),
    }
}

/// Writes `bytes` to the new file `path` (readable by everyone, as `std::fs::write` under the
/// usual umask) and flushes it to disk; `shown` names the file in messages.
fn write_synced(path: &Path, bytes: &[u8], shown: &Path) -> Result<(), CliError> {
    let write = || -> std::io::Result<()> {
        let mut file = File::create(path)?;
        file.write_all(bytes)?;
        file.sync_all()
    };
    write().with_context(|| format!("cannot write {}", shown.display()))?;
    Ok(())
}

/// Lower-case hexadecimal of `bytes`.
fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

/// Writes a line to standard output; a closed pipe (as with `| head`) is not an error.
pub(crate) fn print_line(line: &str) -> Result<(), CliError> {
    let mut out = std::io::stdout().lock();
    match writeln!(out, "{line}") {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => Err(CliError::Failure(
            anyhow::Error::new(e).context("cannot write to standard output"),
        )),
        _ => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slugs_never_leave_the_directory() {
        assert_eq!(slug("../../x", "scene"), "x");
        assert_eq!(slug("/tmp/x", "scene"), "tmp-x");
        assert_eq!(slug("..", "scene"), "scene");
        assert_eq!(slug("", "scene"), "scene");
        assert_eq!(slug("outdoor", "scene"), "outdoor");
        assert_eq!(slug("lispsm:n=2.5", "scene"), "lispsm-n-2.5");
        assert_eq!(slug("a\\b\0c d", "scene"), "a-b-c-d");
        assert_eq!(slug(&"x".repeat(500), "scene").len(), MAX_SLUG_LENGTH);
    }

    #[test]
    fn a_set_replaces_the_previous_set_whole() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("set");
        let first = OutputDir::check(target.clone(), "--out", 0).unwrap();
        first
            .write(
                "test",
                &[
                    ("a.txt".into(), b"a".to_vec()),
                    ("images/b.png".into(), b"b".to_vec()),
                ],
            )
            .unwrap();
        let second = OutputDir::check(target.clone(), "--out", 0).unwrap();
        second
            .write("test", &[("c.txt".into(), b"c".to_vec())])
            .unwrap();
        let mut names: Vec<_> = std::fs::read_dir(&target)
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .collect();
        names.sort();
        assert_eq!(names, ["c.txt", MANIFEST_NAME]);
        let manifest: Manifest =
            serde_json::from_slice(&std::fs::read(target.join(MANIFEST_NAME)).unwrap()).unwrap();
        assert_eq!(manifest.files.len(), 1);
        assert_eq!(manifest.files[0].bytes, 1);
        assert_eq!(
            manifest.files[0].sha256,
            // SHA-256 of "c".
            "2e7d2c03a9507ae265ecf5b5356885a53393a2029d241394997265a1a25aefc6"
        );
        // Nothing but the set is left beside it.
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }

    #[test]
    fn foreign_directories_and_special_files_are_refused() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("mine.txt"), b"user's").unwrap();
        let refused = OutputDir::check(dir.path().to_path_buf(), "--out", 0).unwrap_err();
        assert!(refused.to_string().contains("not a shadowlab output set"));
        let refused = OutputDir::check(PathBuf::from("/dev/null"), "--out", 0).unwrap_err();
        assert!(refused.to_string().contains("a character device"));
        let refused = OutputFile::check(PathBuf::from("/dev/null"), "--out", 0).unwrap_err();
        assert!(refused.to_string().contains("only regular files"));
        let link = dir.path().join("link.png");
        std::os::unix::fs::symlink(dir.path().join("mine.txt"), &link).unwrap();
        let refused = OutputFile::check(link, "--out", 0).unwrap_err();
        assert!(refused.to_string().contains("a symbolic link"));
        let refused = OutputFile::check(dir.path().to_path_buf(), "--out", 0).unwrap_err();
        assert!(refused.to_string().contains("is a directory"));
    }

    #[test]
    fn an_estimate_beyond_the_free_space_is_refused_before_work() {
        let dir = tempfile::tempdir().unwrap();
        let refused = OutputDir::check(dir.path().join("set"), "--out", u64::MAX).unwrap_err();
        assert!(refused.to_string().contains("not enough space for --out"));
    }
}
