//! What a part file says about itself: which render it belongs to (scene hash, options,
//! versions), which part it is, how its PNG is to be made, and its counters. The merge
//! compares these before reading any pixel.

use super::part::Part;
use crate::accel::{AccelOptions, BackendKind};
use crate::output::{Photographic, ToneMap};
use crate::render::RenderOptions;
use crate::stats::RenderStats;
use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};
use std::path::PathBuf;

/// The format of part files this build writes and reads.
pub const PART_FORMAT: &str = "embray-part-3";

/// How the final PNG is made (as the part's `embray render` command line said).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PngSettings {
    /// A `ToneMap` name.
    pub curve: String,
    pub exposure: f32,
    /// The photographic operator's key, burn-out, saturation and gamma.
    pub photographic: [f32; 4],
}

impl PngSettings {
    /// The curve, exposure and photographic parameters, checked as the command line checks
    /// `--tonemap`, `--exposure`, `--key`, `--burn-out`, `--saturation` and `--gamma`.
    pub fn look(&self) -> Result<(ToneMap, f32, Photographic), String> {
        let curve: ToneMap = self.curve.parse().map_err(|e| format!("{e}"))?;
        if !crate::output::exposure_in_range(self.exposure) {
            return Err(format!(
                "the exposure must be a number of stops in [-{max}, {max}], not {}",
                crate::params::show_large(self.exposure),
                max = crate::output::MAX_EXPOSURE_STOPS
            ));
        }
        let [key, burn_out, saturation, gamma] = self.photographic;
        let photographic = Photographic { key, burn_out, saturation, gamma };
        match photographic.problem() {
            Some(problem) => Err(format!("photographic tone mapping: {problem}")),
            None => Ok((curve, self.exposure, photographic)),
        }
    }

    /// As a message shows them.
    fn describe(&self) -> String {
        let [key, burn_out, saturation, gamma] = self.photographic;
        format!(
            "curve {}, exposure {}, photographic key {key}, burn-out {burn_out}, saturation \
             {saturation}, gamma {gamma}",
            self.curve, self.exposure
        )
    }
}

/// The metadata of one part file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PartMeta {
    pub format: String,
    pub embray_version: String,
    /// The Embree library and the kernels it ran (its results can differ between ISAs).
    pub embree: Option<String>,
    /// The scene as named on the command line (for messages only).
    pub scene: String,
    /// SHA-256 over the scene file and every file it read (meshes, material libraries).
    pub scene_hash: String,
    /// Every render option that can change the image, as text.
    pub options: String,
    /// The camera rendered (`camera_fingerprint`): parts of one scene file's different
    /// cameras, or of different `--resolution`s, never merge.
    pub camera: String,
    pub width: u32,
    pub height: u32,
    pub spp: u32,
    pub tile_size: u32,
    pub part: Part,
    pub png: PngSettings,
    /// The EXR's AOVs (an `output::Aovs` list), for the merged image.
    pub aovs: String,
    pub stats: RenderStats,
    /// How long the part took where it ran (reported, never compared).
    pub timing: PartTiming,
}

/// The part's own times: for `embray slurm status` and the merge's summary.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PartTiming {
    pub build_seconds: f64,
    pub render_seconds: f64,
    /// The process's CPU time (user + system, all threads) when the part was encoded: load,
    /// build, render and encoding; what a cluster's accounting would bill.
    #[serde(default)]
    pub cpu_seconds: f64,
    /// Worker threads it rendered with.
    pub threads: usize,
    /// The machine it ran on.
    pub host: String,
}

impl PartMeta {
    /// The fields two parts of one render must share, with their values, for messages:
    /// everything but the part index and the counters.
    pub fn shared_fields(&self) -> Vec<(&'static str, String)> {
        vec![
            ("format", self.format.clone()),
            ("embray version", self.embray_version.clone()),
            ("Embree library", self.embree.clone().unwrap_or_else(|| "not used".into())),
            ("scene contents (SHA-256)", self.scene_hash.clone()),
            ("image size", format!("{}x{}", self.width, self.height)),
            ("camera", self.camera.clone()),
            ("spp", self.spp.to_string()),
            ("split", format!("{} into {} parts", self.part.split, self.part.count)),
            ("tile size", self.tile_size.to_string()),
            ("PNG settings", self.png.describe()),
            ("AOVs", self.aovs.clone()),
        ]
    }
}

/// This process's CPU time so far (user + system, every thread), from `/proc/self/stat`;
/// 0 where that cannot be read.
pub fn process_cpu_seconds() -> f64 {
    let Ok(stat) = std::fs::read_to_string("/proc/self/stat") else {
        return 0.0;
    };
    // The command name (field 2) is in parentheses and may hold spaces: count after it.
    let Some((_, rest)) = stat.rsplit_once(')') else {
        return 0.0;
    };
    let fields: Vec<&str> = rest.split_whitespace().collect();
    // utime and stime are fields 14 and 15 of the line, 11 and 12 after the name; in clock
    // ticks, which Linux reports to user space at 100 per second on every architecture
    // (USER_HZ).
    let ticks = |i: usize| fields.get(i).and_then(|f| f.parse::<u64>().ok()).unwrap_or(0);
    (ticks(11) + ticks(12)) as f64 / 100.0
}

/// The render options that decide the image, as text: the options less the thread count and
/// the progress bar (and the other options that do not change a pixel: the stop, the crop,
/// the phase timing, and on obvhs the traversal counters of `--stats`). What is left must
/// agree between parts and is written into the image. Embree counts by tracing triangles
/// as user geometry with embray's own test, whose hits differ from its native kernels' in
/// the last bits, so there `--stats` stays an option that changes the image.
pub fn options_fingerprint(options: &RenderOptions) -> String {
    let counting = options.count_traversal && options.backend == BackendKind::Embree;
    let canonical = RenderOptions {
        threads: None,
        progress: false,
        stop: None,
        crop: None,
        time_phases: false,
        count_traversal: counting,
        accel: AccelOptions { count_traversal: counting, ..options.accel },
        ..options.clone()
    };
    format!("{canonical:?}")
}

impl PartMeta {
    /// What a final EXR of this render says about how it was made (the `embray` text
    /// attribute, `name: value` lines): the same for the whole render and for the merge of its parts, so that
    /// the two stay one file byte for byte. Times are left out for that reason (they are in
    /// `--stats-json` and the part files). `spp_done` is below `spp` for a stopped render.
    pub fn image_attributes(
        &self,
        spp_done: u32,
        stopped: Option<String>,
    ) -> Vec<(String, String)> {
        let mut fields = vec![
            ("version", self.embray_version.clone()),
            ("embree", self.embree.clone().unwrap_or_else(|| "not used".into())),
            ("scene", self.scene.clone()),
            ("scene_sha256", self.scene_hash.clone()),
            ("camera", self.camera.clone()),
            ("options", self.options.clone()),
            ("spp", spp_done.to_string()),
            ("spp_requested", self.spp.to_string()),
            ("png", format!("{:?}", self.png)),
            ("aovs", self.aovs.clone()),
        ];
        if let Some(reason) = stopped {
            fields.push(("stopped", reason));
        }
        fields.into_iter().map(|(name, value)| (name.to_owned(), value)).collect()
    }
}

/// The camera as text (every field: pose, field of view, lens, size).
pub fn camera_fingerprint(camera: &crate::scene::CameraDesc) -> String {
    format!("{camera:?}")
}

/// The value of the option `name` in a fingerprint, as text (`true`, `Some(2.0)`).
pub fn option_value<'a>(options: &'a str, name: &str) -> Option<&'a str> {
    let start = options.find(&format!(" {name}: "))? + name.len() + 3;
    options[start..].split([',', ' ', '}']).next().filter(|v| !v.is_empty())
}

/// SHA-256 over `files` (their names and contents, in the order given), as hex.
pub fn hash_files(files: &[PathBuf]) -> std::io::Result<String> {
    let mut hasher = Sha256::new();
    for path in files {
        let bytes = crate::scene::read_input_bytes(path)?;
        let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
        hasher.update((name.len() as u64).to_le_bytes());
        hasher.update(name.as_bytes());
        hasher.update((bytes.len() as u64).to_le_bytes());
        hasher.update(&bytes);
    }
    Ok(hasher.finalize().iter().map(|b| format!("{b:02x}")).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn process_cpu_time_counts_work_done() {
        // Busy until the reading has advanced by 0.2 s (ticks are 10 ms); a reader that
        // returns 0 or a constant never gets there.
        let before = process_cpu_seconds();
        let start = std::time::Instant::now();
        let mut x = 0u64;
        while process_cpu_seconds() - before < 0.2 && start.elapsed().as_secs() < 20 {
            for _ in 0..100_000 {
                x = std::hint::black_box(x.wrapping_mul(6364136223846793005).wrapping_add(1));
            }
        }
        let spent = process_cpu_seconds() - before;
        assert!(spent >= 0.2, "CPU time read as {spent} s after {:?} busy", start.elapsed());
    }

    #[test]
    fn option_differences_are_named() {
        let desc = crate::scene::load(&crate::bundled::default_scene()).unwrap();
        let a = RenderOptions::for_scene(&desc);
        let b = RenderOptions { spp: a.spp + 1, threads: Some(3), ..a.clone() };
        let (fa, fb) = (options_fingerprint(&a), options_fingerprint(&b));
        assert_ne!(fa, fb);
        let c = RenderOptions { threads: Some(1), progress: true, ..a.clone() };
        assert_eq!(options_fingerprint(&c), fa, "threads and progress do not change a pixel");
        let obvhs = RenderOptions { backend: BackendKind::Obvhs, ..a.clone() };
        let counted = RenderOptions { count_traversal: true, time_phases: true, ..obvhs.clone() };
        let fingerprint = options_fingerprint(&obvhs);
        assert_eq!(options_fingerprint(&counted), fingerprint, "nor obvhs's counting or timing");
        let embree = RenderOptions { backend: BackendKind::Embree, ..a.clone() };
        let counted = RenderOptions { count_traversal: true, ..embree.clone() };
        assert_ne!(options_fingerprint(&counted), options_fingerprint(&embree), "Embree's hits");
        assert_eq!(option_value(&fa, "first_hit_albedo"), Some("false"));
        assert_eq!(option_value(&fa, "spp"), Some(a.spp.to_string().as_str()));
        assert_eq!(option_value(&fa, "nothing"), None);
    }
}
