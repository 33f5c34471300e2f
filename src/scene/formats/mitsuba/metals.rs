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

/// A `.spd` file's wavelength (nm) and value columns; `#` starts a comment. (The table is
/// made from these files; scenes do not read them.)
#[cfg(test)]
fn parse_spd(text: &str) -> Result<(Vec<f64>, Vec<f64>), String> {
    let (mut wavelengths, mut values) = (Vec::new(), Vec::new());
    for (number, line) in text.lines().enumerate() {
        let data = line.split('#').next().unwrap_or("").trim();
        if data.is_empty() {
            continue;
        }
        let fields: Vec<f64> = data
            .split_whitespace()
            .map(str::parse)
            .collect::<Result<_, _>>()
            .map_err(|_| format!("line {}: not two numbers", number + 1))?;
        match fields[..] {
            [w, v] if w.is_finite() && v.is_finite() => {
                wavelengths.push(w);
                values.push(v);
            }
            _ => return Err(format!("line {}: not two numbers", number + 1)),
        }
    }
    if wavelengths.len() < 2 || wavelengths.windows(2).any(|w| w[1] <= w[0]) {
        return Err("needs two or more increasing wavelengths".to_owned());
    }
    Ok((wavelengths, values))
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
            let (w, v) = parse_spd(&std::fs::read_to_string(&path).unwrap()).unwrap();
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
    fn gold_is_reddish_and_spd_errors_name_the_line() {
        let (eta, k) = rgb_ior("Au").unwrap();
        assert!(eta.x < eta.z && k.x > k.z, "{eta} {k}");
        assert!(parse_spd("400 1\n500 x\n").unwrap_err().contains("line 2"));
    }
}
