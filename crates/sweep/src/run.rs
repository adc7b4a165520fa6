//! Running a shard: its cells, frame by frame (one truth per frame), each stored as it finishes;
//! cells already stored are skipped, so a rerun resumes.

use std::time::Instant;

use shadowlab_analysis::AnalysisError;
use shadowlab_analysis::study::{Ground, measure_setting};
use shadowlab_shadow::ShadowError;

use crate::cells::Plan;
use crate::error::SweepError;
use crate::record::CellRecord;
use crate::shard::{Shard, assign};
use crate::store::SweepDir;

/// What a shard run did.
#[derive(Clone, Debug, PartialEq)]
pub struct ShardRun {
    /// The shard's cells' results, in cell order.
    pub records: Vec<CellRecord>,
    /// How many of them this run measured (the rest were stored already).
    pub measured: usize,
}

/// Runs `shard` of `plan`, storing each cell in `dir` as it finishes and skipping those stored
/// already; `progress(done, total)` after each of the shard's cells. A cell whose frame admits no
/// map (`ShadowError::frame_reason`: an empty or flat focus body, no visible sample, or the
/// technique undefined there) is recorded as not defined, with the reason.
///
/// # Errors
/// A frame's truth failing (bad geometry), a measurement failing other than by a technique being
/// undefined, or a cell that cannot be stored.
pub fn run_shard(
    plan: &Plan,
    shard: Shard,
    dir: &SweepDir,
    mut progress: impl FnMut(usize, usize),
) -> Result<ShardRun, SweepError> {
    let assignment = assign(plan, shard.count)?;
    let mine: Vec<usize> = (0..plan.cells.len())
        .filter(|c| assignment[*c] == shard.index)
        .collect();
    let mut stored: Vec<Option<CellRecord>> = mine.iter().map(|c| dir.load_cell(*c)).collect();
    let mut done = stored.iter().filter(|r| r.is_some()).count();
    let mut measured = 0;
    progress(done, mine.len());
    // Cells are numbered frame by frame, so a frame's missing cells are consecutive here.
    let mut k = 0;
    while k < mine.len() {
        let frame = plan.cells[mine[k]].frame;
        let end = k + mine[k..]
            .iter()
            .take_while(|c| plan.cells[**c].frame == frame)
            .count();
        if stored[k..end].iter().all(Option::is_some) {
            k = end;
            continue;
        }
        let f = &plan.frames[frame];
        let (label, _) = &plan.scenes[f.scene];
        let scene = plan.frame_scene(frame)?;
        let analysis = |e: AnalysisError| SweepError::Analysis(format!("{label}: {e}"));
        let ground = Ground::new(&scene).map_err(analysis)?;
        let visible = ground.eye.visible();
        for slot in k..end {
            if stored[slot].is_some() {
                continue;
            }
            let cell = &plan.cells[mine[slot]];
            let start = Instant::now();
            let measurement = measure_setting(
                &scene,
                (&plan.options[f.scene], &cell.setting),
                &ground,
                ShadowError::frame_reason,
                |_| Ok::<(), AnalysisError>(()),
            )
            .map_err(analysis)?;
            let record = CellRecord::new(
                (cell.index, label, f.camera, f.light),
                (&scene, visible),
                &measurement,
                start.elapsed().as_secs_f64() * 1e3,
            );
            dir.save_cell(&record)?;
            stored[slot] = Some(record);
            measured += 1;
            done += 1;
            progress(done, mine.len());
        }
        k = end;
    }
    let records: Vec<CellRecord> = stored.into_iter().flatten().collect();
    dir.save_shard_tables(shard, &records)?;
    Ok(ShardRun { records, measured })
}
