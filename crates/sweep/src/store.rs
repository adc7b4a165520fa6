//! A sweep directory: what every shard of one sweep writes, so that a rerun resumes and a merge
//! finds everything.
//!
//! ```text
//! DIR/sweep.json              the spec's text and its cell count (the same for every shard)
//! DIR/cells/NNNNNNNN.json     one cell's result (a CellRecord), written whole or not at all
//! DIR/shard-I-of-N/results.csv, results.parquet   a finished shard's cells, in cell order
//! ```
//!
//! Every file is written to a temporary name in its directory and renamed into place, so a
//! killed shard leaves no partial cell, and shards may share a directory.

use std::fs;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use serde::{Deserialize, Serialize};

use crate::error::SweepError;
use crate::record::CellRecord;
use crate::shard::Shard;
use crate::table;

/// What identifies a sweep in its directory.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct SweepIdentity {
    /// The spec, as written.
    pub spec: String,
    /// How many cells it has.
    pub cells: usize,
}

/// A sweep's directory, opened for one sweep.
#[derive(Clone, Debug)]
pub struct SweepDir {
    root: PathBuf,
    identity: SweepIdentity,
}

/// The sweep's identity file in a sweep directory.
pub const IDENTITY_FILE: &str = "sweep.json";

/// The directory of cell files.
pub const CELLS_DIR: &str = "cells";

fn io(path: &Path, what: &str, e: &std::io::Error) -> SweepError {
    SweepError::Output(format!("{}: cannot {what}: {e}", path.display()))
}

/// The merged output of a whole sweep, inside its directory.
pub const MERGED_DIR: &str = "merged";

/// The Slurm scripts of a sweep, inside its directory.
pub const SLURM_DIR: &str = "slurm";

/// Whether a directory entry's name is one a sweep directory holds (its identity, cells, shard
/// tables, merged output, Slurm scripts, or a hidden temporary: [`write_atomically`]'s, an output
/// set's staging): what another shard starting at the same moment may already have made.
fn is_sweep_entry(name: &str) -> bool {
    [IDENTITY_FILE, CELLS_DIR, MERGED_DIR, SLURM_DIR].contains(&name)
        || name.starts_with("shard-")
        || name.starts_with('.')
}

/// Writes `bytes` to `path` through a temporary file in the same directory and a rename.
///
/// # Errors
/// [`SweepError::Output`] naming the path.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> Result<(), SweepError> {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    // Unique to this process and call: shards (processes) and threads may write one name at once.
    static CALLS: AtomicU64 = AtomicU64::new(0);
    let call = CALLS.fetch_add(1, Ordering::Relaxed);
    let temporary = path.with_file_name(format!(".{name}.{}.{call}.partial", std::process::id()));
    fs::write(&temporary, bytes).map_err(|e| io(&temporary, "write", &e))?;
    fs::rename(&temporary, path).map_err(|e| {
        let _ = fs::remove_file(&temporary);
        io(path, "rename into place", &e)
    })
}

impl SweepDir {
    /// Opens (creating it if need be) the sweep directory `root` for the sweep `identity`.
    ///
    /// # Errors
    /// [`SweepError::Shard`] if `root` holds another sweep (its `sweep.json` differs) or files
    /// that are not a sweep's, naming it;
    /// [`SweepError::Output`] if it cannot be created or written.
    pub fn create(root: &Path, identity: SweepIdentity) -> Result<Self, SweepError> {
        let foreign = !root.join(IDENTITY_FILE).exists()
            && fs::read_dir(root).is_ok_and(|entries| {
                entries
                    .flatten()
                    .any(|e| !is_sweep_entry(&e.file_name().to_string_lossy()))
            });
        if foreign {
            return Err(SweepError::Shard(format!(
                "{}: holds files that are not a sweep's (no {IDENTITY_FILE}); give --out a new, an empty or a sweep directory",
                root.display()
            )));
        }
        fs::create_dir_all(root.join(CELLS_DIR)).map_err(|e| io(root, "create", &e))?;
        if Self::read_identity(root).is_err() {
            // Shards starting together all write it; the same sweep writes the same bytes.
            let text = serde_json::to_string_pretty(&identity).expect("plain data");
            write_atomically(&root.join(IDENTITY_FILE), text.as_bytes())?;
        }
        // Read back, so that of two different sweeps started into one directory at once, the one
        // whose identity did not land stops here.
        if Self::read_identity(root)? != identity {
            return Err(SweepError::Shard(format!(
                "{}: holds the results of another sweep (its {IDENTITY_FILE} names a different spec); give --out another directory",
                root.display()
            )));
        }
        Ok(Self {
            root: root.to_path_buf(),
            identity,
        })
    }

    /// Opens an existing sweep directory (to merge it).
    ///
    /// # Errors
    /// [`SweepError::Shard`] if `root` is not a sweep directory.
    pub fn open(root: &Path) -> Result<Self, SweepError> {
        let identity = Self::read_identity(root)?;
        Ok(Self {
            root: root.to_path_buf(),
            identity,
        })
    }

    fn read_identity(root: &Path) -> Result<SweepIdentity, SweepError> {
        let path = root.join(IDENTITY_FILE);
        let text = fs::read_to_string(&path).map_err(|e| {
            SweepError::Shard(format!(
                "{}: not a sweep directory ({IDENTITY_FILE}: {e})",
                root.display()
            ))
        })?;
        serde_json::from_str(&text)
            .map_err(|e| SweepError::Shard(format!("{}: malformed: {e}", path.display())))
    }

    /// The sweep it holds.
    #[must_use]
    pub fn identity(&self) -> &SweepIdentity {
        &self.identity
    }

    fn cell_path(&self, cell: usize) -> PathBuf {
        self.root.join(CELLS_DIR).join(format!("{cell:08}.json"))
    }

    /// Cell `cell`'s result, if it is complete (a cell file that does not parse, or that holds
    /// another cell, is not).
    #[must_use]
    pub fn load_cell(&self, cell: usize) -> Option<CellRecord> {
        let text = fs::read_to_string(self.cell_path(cell)).ok()?;
        serde_json::from_str::<CellRecord>(&text)
            .ok()
            .filter(|r| r.cell == cell as u64)
    }

    /// Stores a cell's result.
    ///
    /// # Errors
    /// [`SweepError::Output`] naming the file.
    pub fn save_cell(&self, record: &CellRecord) -> Result<(), SweepError> {
        let cell = usize::try_from(record.cell).expect("a cell number of this sweep");
        let text = serde_json::to_string_pretty(record).expect("plain data");
        write_atomically(&self.cell_path(cell), text.as_bytes())
    }

    /// Writes a finished shard's table (CSV and Parquet) of `records`.
    ///
    /// # Errors
    /// [`SweepError::Output`] naming the file.
    pub fn save_shard_tables(
        &self,
        shard: Shard,
        records: &[CellRecord],
    ) -> Result<PathBuf, SweepError> {
        let dir = self.root.join(shard.dir_name());
        fs::create_dir_all(&dir).map_err(|e| io(&dir, "create", &e))?;
        write_atomically(&dir.join("results.csv"), table::csv(records).as_bytes())?;
        let parquet = table::parquet(records).map_err(|e| SweepError::Output(e.to_string()))?;
        write_atomically(&dir.join("results.parquet"), &parquet)?;
        Ok(dir)
    }
}

/// Every cell of the sweep held by `dirs` (which must hold the same sweep), each from the first
/// directory that has it, in cell order.
///
/// # Errors
/// [`SweepError::Shard`] if the directories hold different sweeps, or cells are missing (how
/// many, and the first few).
pub fn collect(dirs: &[SweepDir]) -> Result<(SweepIdentity, Vec<CellRecord>), SweepError> {
    let Some(first) = dirs.first() else {
        return Err(SweepError::Shard("nothing to merge".into()));
    };
    for dir in &dirs[1..] {
        if dir.identity != first.identity {
            return Err(SweepError::Shard(format!(
                "{} and {} hold different sweeps (their {IDENTITY_FILE} differ)",
                first.root.display(),
                dir.root.display()
            )));
        }
    }
    let mut records = Vec::with_capacity(first.identity.cells);
    let mut missing = Vec::new();
    for cell in 0..first.identity.cells {
        match dirs.iter().find_map(|d| d.load_cell(cell)) {
            Some(record) => records.push(record),
            None => missing.push(cell),
        }
    }
    if !missing.is_empty() {
        let shown: Vec<String> = missing.iter().take(8).map(ToString::to_string).collect();
        return Err(SweepError::Shard(format!(
            "{} of {} cells have no result yet (cells {}{}): run the missing shards, or rerun them to resume",
            missing.len(),
            first.identity.cells,
            shown.join(", "),
            if missing.len() > shown.len() {
                ", …"
            } else {
                ""
            }
        )));
    }
    Ok((first.identity.clone(), records))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn identity(spec: &str) -> SweepIdentity {
        SweepIdentity {
            spec: spec.into(),
            cells: 3,
        }
    }

    #[test]
    fn shards_starting_together_all_open_the_directory() {
        let dir = tempfile::tempdir().unwrap();
        let root = dir.path().join("sweep");
        let opened: Vec<bool> = std::thread::scope(|scope| {
            let handles: Vec<_> = (0..8)
                .map(|_| scope.spawn(|| SweepDir::create(&root, identity("a")).is_ok()))
                .collect();
            handles.into_iter().map(|h| h.join().unwrap()).collect()
        });
        assert!(opened.iter().all(|o| *o), "{opened:?}");
        assert_eq!(SweepDir::open(&root).unwrap().identity(), &identity("a"));
    }

    #[test]
    fn another_sweep_or_foreign_files_are_refused() {
        let dir = tempfile::tempdir().unwrap();
        SweepDir::create(dir.path(), identity("a")).unwrap();
        let e = SweepDir::create(dir.path(), identity("b")).unwrap_err();
        assert!(e.to_string().contains("another sweep"), "{e}");
        let foreign = tempfile::tempdir().unwrap();
        fs::write(foreign.path().join("notes.txt"), "mine").unwrap();
        let e = SweepDir::create(foreign.path(), identity("a")).unwrap_err();
        assert!(e.to_string().contains("not a sweep's"), "{e}");
    }

    #[test]
    fn a_cell_file_of_another_cell_or_cut_short_is_not_complete() {
        let dir = tempfile::tempdir().unwrap();
        let sweep = SweepDir::create(dir.path(), identity("a")).unwrap();
        assert_eq!(sweep.load_cell(1), None);
        fs::write(sweep.cell_path(1), "{\"cell\": 1, \"sce").unwrap();
        assert_eq!(sweep.load_cell(1), None);
    }
}
