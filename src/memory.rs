//! Memory, bounded before it is spent: what a run will allocate, estimated from the sizes that
//! drive it, against a budget — by default a fraction of the memory available to the process
//! (the cgroup's limit less its usage, or `/proc/meminfo`'s `MemAvailable`, whichever is less),
//! or `--memory-budget`.
//!
//! The per-pixel and per-texel costs are the peak resident sizes measured on the built-in and
//! test scenes (docs/benchmarks.md, "memory model"), rounded up: the estimate is meant to be an
//! upper bound of the peak, never a forecast of it.

use std::fmt;

use crate::error::CliError;

/// The fraction of the available memory a run may plan to use by default; the rest is left to the
/// system and to the estimate's error.
pub(crate) const DEFAULT_BUDGET_FRACTION: f64 = 0.75;

/// Resident size of the program before any scene (code, allocator, thread pool).
const BASE_BYTES: u64 = 64 << 20;
/// Per triangle of the scene: positions, indices, normals and the ray-casting BVH.
const BYTES_PER_TRIANGLE: u64 = 256;
/// Per eye pixel of `render` and `compare`: the eye pass (depth, triangle, position, normal), the
/// shadow state and the shaded picture (measured: 82 and 91 bytes).
const FRAME_BYTES_PER_PIXEL: u64 = 112;
/// Per eye pixel of the study commands (`analyze`, `sweep-angle`, `temporal`): the eye pass, the
/// exact truth, per-pixel footprints and their sorted copies, the pictures (measured: 190 bytes).
const STUDY_BYTES_PER_PIXEL: u64 = 240;
/// Per texel of each map kept: nearest and second-nearest depth (f64 each).
const MAP_BYTES_PER_TEXEL: u64 = 16;
/// Per texel of the map being rasterized: the tiled depth keys, and the pictures of a map
/// (`render`).
const RASTER_BYTES_PER_TEXEL: u64 = 16;
/// Per eye pixel, added by `--export`: the eye pass's files encoded together (measured: 85 bytes).
const EXPORT_BYTES_PER_PIXEL: u64 = 96;
/// Per texel of each kept map, added by `--export`: its depth as f32 and encoded (measured: 4.8
/// bytes).
const EXPORT_BYTES_PER_TEXEL: u64 = 8;

/// A number of bytes, parsed from `N`, `NK`, `NM`, `NG` or `NT` (powers of 1024, an optional `iB`
/// or `B` after the letter) and shown in MiB or GiB.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Bytes(pub(crate) u64);

impl Bytes {
    /// Parses a size as `--memory-budget` takes it.
    pub(crate) fn parse(text: &str) -> Result<Self, String> {
        let trimmed = text.trim();
        let split = trimmed
            .find(|c: char| !(c.is_ascii_digit() || c == '.'))
            .unwrap_or(trimmed.len());
        let (number, unit) = trimmed.split_at(split);
        let shift = match unit.trim().to_ascii_uppercase().as_str() {
            "" | "B" => 0,
            "K" | "KB" | "KIB" => 10,
            "M" | "MB" | "MIB" => 20,
            "G" | "GB" | "GIB" => 30,
            "T" | "TB" | "TIB" => 40,
            _ => {
                return Err(format!(
                    "{text:?} is not a size: give bytes, or a number followed by K, M, G or T"
                ));
            }
        };
        let value: f64 = number.parse().map_err(|_| {
            format!("{text:?} is not a size: give bytes, or a number followed by K, M, G or T")
        })?;
        let bytes = value * 2f64.powi(shift);
        if !(bytes >= 1.0 && bytes < 2f64.powi(63)) {
            return Err(format!(
                "{text:?} is out of range: between 1 byte and 8 EiB"
            ));
        }
        #[expect(
            clippy::cast_possible_truncation,
            clippy::cast_sign_loss,
            reason = "checked to lie in [1, 2^63)"
        )]
        Ok(Self(bytes as u64))
    }
}

impl fmt::Display for Bytes {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        #[expect(clippy::cast_precision_loss, reason = "shown to one decimal")]
        let value = self.0 as f64;
        if self.0 >= 1 << 30 {
            write!(f, "{:.1} GiB", value / f64::from(1u32 << 30))
        } else {
            write!(f, "{:.1} MiB", value / f64::from(1u32 << 20))
        }
    }
}

/// What drives a run's memory.
#[derive(Clone, Debug)]
pub(crate) struct Workload {
    /// The scene's triangles.
    pub(crate) triangles: u64,
    /// The eye image, width × height, and whether the run is a study (truth and footprints kept
    /// per pixel) or a frame.
    pub(crate) eye: (u32, u32),
    pub(crate) study: bool,
    /// The largest map side and the most maps one frame keeps at once.
    pub(crate) resolution: u32,
    pub(crate) maps: u64,
    /// The flags or fields that set each size, for the message.
    pub(crate) eye_source: &'static str,
    pub(crate) map_source: &'static str,
    /// Whether every per-pixel result is exported (`--export`).
    pub(crate) export: bool,
}

impl Workload {
    /// The workload of `scene`'s eye image, `maps` maps of `resolution`² at once, in a study or a
    /// single frame; `eye_source` and `map_source` name what set the sizes.
    pub(crate) fn of(
        scene: &shadowlab_scene::Scene,
        study: bool,
        resolution: u32,
        maps: u64,
        eye_source: &'static str,
        map_source: &'static str,
    ) -> Self {
        Self {
            triangles: scene.mesh.triangles().len() as u64,
            eye: (scene.camera.width, scene.camera.height),
            study,
            resolution,
            maps,
            eye_source,
            map_source,
            export: false,
        }
    }

    /// The workload with `--export`'s encoded files added, if `export`.
    pub(crate) fn exporting(self, export: bool) -> Self {
        Self { export, ..self }
    }

    /// The estimated peak, in bytes, and its parts.
    fn estimate(&self) -> (u64, u64, u64) {
        let pixels = u64::from(self.eye.0) * u64::from(self.eye.1);
        let per_pixel = if self.study {
            STUDY_BYTES_PER_PIXEL
        } else {
            FRAME_BYTES_PER_PIXEL
        };
        let (export_pixel, export_texel) = if self.export {
            (EXPORT_BYTES_PER_PIXEL, EXPORT_BYTES_PER_TEXEL)
        } else {
            (0, 0)
        };
        let texels = u64::from(self.resolution) * u64::from(self.resolution);
        let eye = pixels.saturating_mul(per_pixel + export_pixel);
        let maps = texels.saturating_mul(
            self.maps
                .saturating_mul(MAP_BYTES_PER_TEXEL + export_texel)
                .saturating_add(RASTER_BYTES_PER_TEXEL),
        );
        let total = BASE_BYTES
            .saturating_add(self.triangles.saturating_mul(BYTES_PER_TRIANGLE))
            .saturating_add(eye)
            .saturating_add(maps);
        (total, eye, maps)
    }
}

/// The memory available to this process: the cgroup (v2) limit less its usage, and the system's
/// `MemAvailable`, whichever is less; `None` where neither can be read.
fn available() -> Option<u64> {
    let read = |path: &str| std::fs::read_to_string(path).ok();
    let cgroup = read("/sys/fs/cgroup/memory.max")
        .and_then(|max| max.trim().parse::<u64>().ok())
        .map(|max| {
            let used = read("/sys/fs/cgroup/memory.current")
                .and_then(|c| c.trim().parse::<u64>().ok())
                .unwrap_or(0);
            max.saturating_sub(used)
        });
    let system = read("/proc/meminfo").and_then(|info| {
        info.lines()
            .find_map(|line| line.strip_prefix("MemAvailable:"))
            .and_then(|rest| {
                rest.trim()
                    .trim_end_matches("kB")
                    .trim()
                    .parse::<u64>()
                    .ok()
            })
            .map(|kib| kib.saturating_mul(1024))
    });
    match (cgroup, system) {
        (Some(a), Some(b)) => Some(a.min(b)),
        (a, b) => a.or(b),
    }
}

/// Refuses `workload` when its estimate exceeds the budget: `stated` (`--memory-budget`) or
/// [`DEFAULT_BUDGET_FRACTION`] of the available memory. The message gives the estimate, its
/// parts and the flags that drive them.
pub(crate) fn check(workload: &Workload, stated: Option<Bytes>) -> Result<(), CliError> {
    let (budget, whence) = match stated {
        Some(b) => (b.0, "--memory-budget".to_string()),
        None => {
            let Some(available) = available() else {
                return Ok(());
            };
            #[expect(
                clippy::cast_possible_truncation,
                clippy::cast_sign_loss,
                clippy::cast_precision_loss,
                reason = "a fraction of a byte count"
            )]
            let budget = (available as f64 * DEFAULT_BUDGET_FRACTION) as u64;
            (
                budget,
                format!(
                    "{:.0} % of the {} available",
                    DEFAULT_BUDGET_FRACTION * 100.0,
                    Bytes(available)
                ),
            )
        }
    };
    let (total, eye, maps) = workload.estimate();
    if total <= budget {
        return Ok(());
    }
    let (w, h) = workload.eye;
    Err(CliError::Input(format!(
        "the run would need about {} of memory — the {w}x{h} eye image {} ({}), {} map(s) of \
         {r}² {} ({}) — above the budget of {} ({whence}); lower them, or raise --memory-budget",
        Bytes(total),
        Bytes(eye),
        workload.eye_source,
        workload.maps,
        Bytes(maps),
        workload.map_source,
        Bytes(budget),
        r = workload.resolution,
    )))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_parse_in_powers_of_1024() {
        assert_eq!(Bytes::parse("512"), Ok(Bytes(512)));
        assert_eq!(Bytes::parse("4K"), Ok(Bytes(4096)));
        assert_eq!(Bytes::parse("1.5GiB"), Ok(Bytes(3 << 29)));
        assert_eq!(Bytes::parse("2 T"), Ok(Bytes(2 << 40)));
        for bad in ["", "-1", "0", "1X", "G", "nan", "1e400", "99999999999T"] {
            assert!(Bytes::parse(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn the_estimate_grows_with_every_size_and_is_refused_above_the_budget() {
        let small = Workload {
            triangles: 1000,
            eye: (1024, 768),
            study: true,
            resolution: 1024,
            maps: 1,
            eye_source: "camera.image",
            map_source: "--resolution, --partitions",
            export: false,
        };
        let base = small.estimate().0;
        for bigger in [
            Workload {
                eye: (2048, 768),
                ..small.clone()
            },
            Workload {
                resolution: 2048,
                ..small.clone()
            },
            Workload {
                maps: 4,
                ..small.clone()
            },
            Workload {
                triangles: 10_000_000,
                ..small.clone()
            },
            small.clone().exporting(true),
        ] {
            assert!(bigger.estimate().0 > base);
        }
        assert!(check(&small, Some(Bytes(base))).is_ok());
        let refused = check(&small, Some(Bytes(base - 1)))
            .unwrap_err()
            .to_string();
        assert!(
            refused.contains("--memory-budget") && refused.contains("camera.image"),
            "{refused}"
        );
        let huge = Workload {
            eye: (16384, 16384),
            resolution: 16384,
            maps: 16,
            ..small
        };
        assert!(huge.estimate().0 > 32 << 30);
    }
}
