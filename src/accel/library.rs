//! The backends compiled into this binary, and which Embree library runs.

/// The Embree library linked into this binary, as it runs on this CPU.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub struct EmbreeLibrary {
    /// `major.minor.patch`, from the library itself (not from the header).
    pub version: String,
    /// The kernels Embree dispatches to here: "AVX-512", "AVX2", "AVX", "SSE4.2" or "SSE2".
    pub isa: &'static str,
}

impl std::fmt::Display for EmbreeLibrary {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Embree {} ({} kernels)", self.version, self.isa)
    }
}

/// The running Embree; `None` without the Embree backend or when it cannot start.
pub fn embree_library() -> Option<EmbreeLibrary> {
    #[cfg(feature = "embree")]
    return super::embree::library().ok();
    #[cfg(not(feature = "embree"))]
    None
}

/// What this binary's backends are, for `--version` and `info`: e.g.
/// "Embree 3.13.5 (AVX2 kernels), obvhs". An Embree that cannot start says why.
pub fn backends_description() -> String {
    let backends = [embree_description(), cfg!(feature = "obvhs").then(|| "obvhs".to_owned())];
    backends.into_iter().flatten().collect::<Vec<_>>().join(", ")
}

/// The Embree part of `backends_description`, if the binary has the backend.
fn embree_description() -> Option<String> {
    #[cfg(feature = "embree")]
    return Some(match super::embree::library() {
        Ok(library) => library.to_string(),
        Err(e) => format!("Embree (cannot start: {e})"),
    });
    #[cfg(not(feature = "embree"))]
    None
}
