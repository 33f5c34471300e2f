//! Measured complex indices of refraction of conductors (`material="Au"`), as Mitsuba 3's
//! RGB variants use them: its `ior/<name>.eta.spd` and `.k.spd` spectra converted to linear
//! RGB by `spectrum::list_to_srgb` (unbounded, without D65). The converted values are
//! embedded (an installed embray has no data folder); a test recomputes every one from the
//! spectra when `../shared/data/mitsuba/ior` is there.

use glam::DVec3;

/// The (eta, k) of the conductor `name` in linear RGB, if embray knows it.
pub(super) fn rgb_ior(name: &str) -> Option<(DVec3, DVec3)> {
    METALS
        .iter()
        .find(|(known, _, _)| *known == name)
        .map(|(_, eta, k)| (DVec3::from_array(*eta), DVec3::from_array(*k)))
}

/// The names embray knows, for messages.
pub(super) fn names() -> impl Iterator<Item = &'static str> {
    METALS.iter().map(|(name, _, _)| *name)
}

include!("metals_table.rs");

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::formats::mitsuba::spectrum::list_to_srgb;

    fn ior_dir() -> std::path::PathBuf {
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data/mitsuba/ior")
    }

    /// The RGB of `name`'s spectra, as Mitsuba's `ior_from_file` converts them.
    fn from_spectra(name: &str) -> (DVec3, DVec3) {
        let convert = |suffix: &str| {
            let path = ior_dir().join(format!("{name}.{suffix}.spd"));
            let text = std::fs::read_to_string(&path).unwrap();
            let (w, v): (Vec<f64>, Vec<f64>) =
                super::super::spd::parse(&text).unwrap().into_iter().unzip();
            list_to_srgb(&w, &v, false, false)
        };
        (convert("eta"), convert("k"))
    }

    #[test]
    #[cfg_attr(not(mitsuba_data), ignore = "needs Mitsuba's ior/ data at ../shared/data/mitsuba")]
    fn the_embedded_table_is_the_spectra_converted() {
        let mut names: Vec<String> = std::fs::read_dir(ior_dir())
            .unwrap()
            .filter_map(|e| {
                let name = e.unwrap().file_name().to_string_lossy().into_owned();
                name.strip_suffix(".eta.spd").map(str::to_owned)
            })
            .collect();
        names.sort();
        // EMBRAY_PRINT_METALS=1 prints the table (to regenerate `metals_table.rs`).
        if std::env::var_os("EMBRAY_PRINT_METALS").is_some() {
            for name in &names {
                let (eta, k) = from_spectra(name);
                println!("    ({name:?}, {:?}, {:?}),", eta.to_array(), k.to_array());
            }
        }
        assert_eq!(names, super::names().collect::<Vec<_>>());
        for name in &names {
            let (eta, k) = from_spectra(name);
            let (table_eta, table_k) = rgb_ior(name).unwrap();
            assert!((eta - table_eta).abs().max_element() < 1e-12, "{name}: {eta} vs {table_eta}");
            assert!((k - table_k).abs().max_element() < 1e-12, "{name}: {k} vs {table_k}");
        }
    }

    #[test]
    fn gold_is_reddish() {
        let (eta, k) = rgb_ior("Au").unwrap();
        assert!(eta.x < eta.z && k.x > k.z, "{eta} {k}");
    }
}
