//! Progress on standard error, drawn only when it is a terminal (indicatif hides it otherwise).

use indicatif::{ProgressBar, ProgressStyle};

/// How often a bar redraws its elapsed time while a step runs.
const TICK: std::time::Duration = std::time::Duration::from_millis(250);

/// A bar of steps (set its length and position as they go), headed `what`. It ticks on its own,
/// so a long step (a wide filter at a high resolution) shows its elapsed time.
pub(crate) fn bar(what: &str) -> ProgressBar {
    let bar = ProgressBar::new(0);
    bar.set_style(
        ProgressStyle::with_template("{msg} [{bar:30}] {pos}/{len} {elapsed}")
            .expect("a valid template")
            .progress_chars("=> "),
    );
    bar.set_message(what.to_string());
    bar.enable_steady_tick(TICK);
    bar
}

/// A spinner for one long step, headed `what`, with its elapsed time.
pub(crate) fn spinner(what: &str) -> ProgressBar {
    let spinner = ProgressBar::new_spinner();
    spinner.set_style(
        ProgressStyle::with_template("{spinner} {msg} {elapsed}").expect("a valid template"),
    );
    spinner.set_message(what.to_string());
    spinner.enable_steady_tick(TICK);
    spinner
}
