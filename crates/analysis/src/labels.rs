//! How techniques and filters are named in tables, pictures and pages (the report, its HTML page,
//! the pictures' titles, sweeps), in one place below all of them.

use shadowlab_shadow::{Filter, MomentMethod, Technique};

/// The technique's name in tables: its key, and its parameter after a slash where it is not the
/// default (`lispsm/minimax`, `logarithmic/faces`, `optimal/refit`).
#[must_use]
pub fn technique_label(technique: Technique) -> String {
    match technique.parameter() {
        Some(parameter) => format!("{}/{parameter}", technique.key()),
        None => technique.key().into(),
    }
}

/// A filter as the command line writes it.
#[must_use]
pub fn filter_label(filter: &Filter) -> String {
    match filter {
        Filter::Nearest => "nearest".into(),
        Filter::Pcf { size } => format!("pcf:{size}"),
        Filter::Disk { taps, radius, seed } => format!("disk:{taps},{radius},{seed}"),
        Filter::Vsm {
            size,
            min_variance,
            prefilter,
        } => format!("vsm:{size},{min_variance}{prefilter}"),
        Filter::Moments {
            size,
            method,
            prefilter,
        } => {
            let numbers = match method {
                MomentMethod::Esm { exponent } => format!("esm:{size},{exponent}"),
                MomentMethod::Evsm2 {
                    exponent,
                    min_variance,
                } => format!("evsm2:{size},{exponent},{min_variance}"),
                MomentMethod::Evsm4 {
                    positive,
                    negative,
                    min_variance,
                } => format!("evsm4:{size},{positive},{negative},{min_variance}"),
                MomentMethod::Msm { alpha } => format!("msm:{size},{alpha}"),
            };
            // The prefilter's knobs after `@`, the defaults (box, exact) left out as before.
            format!("{numbers}{prefilter}")
        }
    }
}
