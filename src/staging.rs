//! Staging: where an output set is written before it is moved into place, and what happens to it
//! when the run does not finish.
//!
//! A staging entry is named `.shadowlab-staging-<pid>-<random>` and lives beside its destination
//! (same directory, so same file system: the final move is a rename). Three ways it goes away:
//! * the run finishes: the entry is renamed into place (or, for a directory, exchanged with the
//!   previous set, which then sits under the staging name and is removed);
//! * the run fails or receives SIGINT or SIGTERM: the entry is removed ([`install_interrupt_cleanup`]
//!   and the owners' `Drop`);
//! * the run is killed (SIGKILL, power loss): the entry stays, and the next run that writes into the
//!   same directory removes it ([`remove_orphans`]), recognising it by a process id that is no longer
//!   a running shadowlab.
//!
//! Linux only: process liveness is read from `/proc`, the exchange is `renameat2`.

use std::path::{Path, PathBuf};
use std::sync::{Mutex, Once, PoisonError};

/// The name prefix of every staging entry.
pub(crate) const STAGING_PREFIX: &str = ".shadowlab-staging-";

/// The name of the running program as `/proc/<pid>/comm` shows it; staging entries whose owner
/// has another name belong to a dead run whose process id was reused.
const PROGRAM_NAME: &str = "shadowlab";

/// Staging entries of this process that an interruption must remove.
static PENDING: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// The prefix of this process's staging entries: `.shadowlab-staging-<pid>-`.
pub(crate) fn own_prefix() -> String {
    format!("{STAGING_PREFIX}{}-", std::process::id())
}

/// Registers `path` for removal if the process is interrupted before [`forget`] is called.
pub(crate) fn remember(path: &Path) {
    PENDING
        .lock()
        .unwrap_or_else(PoisonError::into_inner)
        .push(path.to_path_buf());
}

/// Unregisters `path` (it was moved into place or removed).
pub(crate) fn forget(path: &Path) {
    PENDING
        .lock()
        .unwrap_or_else(PoisonError::into_inner)
        .retain(|p| p != path);
}

/// Removes a staging entry, file or directory; a missing one is not an error.
pub(crate) fn remove(path: &Path) -> std::io::Result<()> {
    let result = match std::fs::symlink_metadata(path) {
        Ok(meta) if meta.is_dir() => std::fs::remove_dir_all(path),
        Ok(_) => std::fs::remove_file(path),
        Err(e) => Err(e),
    };
    match result {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(()),
        other => other,
    }
}

/// Installs (once) handlers for SIGINT and SIGTERM that remove this process's staging entries,
/// say so on standard error and end the process with the shell's code for the signal (128 + its
/// number: 130 for SIGINT, 143 for SIGTERM). Without them the default action would end the process
/// and leave the entries behind.
pub(crate) fn install_interrupt_cleanup() {
    static INSTALLED: Once = Once::new();
    INSTALLED.call_once(|| {
        use signal_hook::consts::{SIGINT, SIGTERM};
        let Ok(mut signals) = signal_hook::iterator::Signals::new([SIGINT, SIGTERM]) else {
            // Without handlers an interruption leaves staging entries for the next run to remove.
            return;
        };
        std::thread::spawn(move || {
            if let Some(signal) = signals.forever().next() {
                let pending = PENDING.lock().unwrap_or_else(PoisonError::into_inner);
                for path in pending.iter() {
                    // Best effort: the next run removes what this could not.
                    let _ = remove(path);
                }
                let name = if signal == SIGINT {
                    "SIGINT"
                } else {
                    "SIGTERM"
                };
                eprintln!("shadowlab: interrupted by {name}; nothing was written");
                std::process::exit(128 + signal);
            }
        });
    });
}

/// Whether process `pid` is a running shadowlab (on Linux, from `/proc/<pid>/comm`).
fn is_running_shadowlab(pid: u32) -> bool {
    std::fs::read_to_string(format!("/proc/{pid}/comm"))
        .is_ok_and(|comm| comm.trim_end() == PROGRAM_NAME)
}

/// The owner's process id in a staging entry's name, if the name is one.
fn owner(name: &str) -> Option<u32> {
    name.strip_prefix(STAGING_PREFIX)?
        .split('-')
        .next()?
        .parse()
        .ok()
}

/// Removes the staging entries in `dir` left by runs that are no longer running (killed before
/// they could clean up). Entries of running shadowlab processes, this one included, are kept.
/// Returns the entries removed.
pub(crate) fn remove_orphans(dir: &Path) -> Vec<PathBuf> {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Vec::new();
    };
    let mut removed = Vec::new();
    for entry in entries.flatten() {
        let name = entry.file_name();
        let Some(pid) = name.to_str().and_then(owner) else {
            continue;
        };
        if pid != std::process::id() && !is_running_shadowlab(pid) {
            let path = entry.path();
            if remove(&path).is_ok() {
                removed.push(path);
            }
        }
    }
    removed.sort();
    removed
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn owner_is_read_from_the_name() {
        assert_eq!(owner(".shadowlab-staging-123-abc"), Some(123));
        assert_eq!(owner(".shadowlab-staging-x-abc"), None);
        assert_eq!(owner("report.md"), None);
    }

    #[test]
    fn orphans_of_dead_runs_are_removed_and_live_ones_kept() {
        let dir = tempfile::tempdir().unwrap();
        // Process ids above the kernel's limit (2^22) are never running.
        let dead = dir.path().join(format!("{STAGING_PREFIX}99999999-abc"));
        std::fs::create_dir(&dead).unwrap();
        std::fs::write(dead.join("report.md"), b"half").unwrap();
        let dead_file = dir.path().join(format!("{STAGING_PREFIX}99999998-def"));
        std::fs::write(&dead_file, b"").unwrap();
        let mine = dir.path().join(format!("{}xyz", own_prefix()));
        std::fs::create_dir(&mine).unwrap();
        let unrelated = dir.path().join("keep.txt");
        std::fs::write(&unrelated, b"user's").unwrap();
        let removed = remove_orphans(dir.path());
        assert_eq!(removed, vec![dead_file.clone(), dead.clone()]);
        assert!(!dead.exists() && !dead_file.exists());
        assert!(mine.exists() && unrelated.exists());
    }
}
