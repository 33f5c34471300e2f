//! Which Embree is running: its version and the SIMD kernels it dispatches to.
//!
//! Embree's SSE, AVX2 and AVX-512 kernels can return different hits for the same ray
//! (embree issue #423), so a render's record names them. Embree has no property for the
//! kernel it picked; it picks the widest of its compiled targets (SSE2, SSE4.2, AVX, AVX2,
//! AVX-512 in Debian's packages and in the embreex wheel: `verbose=1` lists them) that the
//! CPU supports. `NATIVE_RAY16/8/4_SUPPORTED` report AVX-512 / AVX / SSE2 enabled on this
//! CPU; the CPU's own flags tell AVX2 from AVX and SSE4.2 from SSE2.

use super::device::Device;
use super::ffi;
use crate::accel::{AccelError, EmbreeLibrary};
use std::sync::OnceLock;

/// The library's version and kernels, asked once per process.
pub fn library() -> Result<EmbreeLibrary, AccelError> {
    static LIBRARY: OnceLock<Result<EmbreeLibrary, String>> = OnceLock::new();
    LIBRARY
        .get_or_init(|| query(&Device::new("threads=1").map_err(|e| e.to_string())?))
        .clone()
        .map_err(AccelError::Embree)
}

fn query(device: &Device) -> Result<EmbreeLibrary, String> {
    use ffi::RTCDeviceProperty as P;
    let property = |p| device.property(p);
    let version = property(P::VERSION);
    if version <= 0 {
        return Err(format!("the library reports version {version}"));
    }
    let isa = if property(P::NATIVE_RAY16_SUPPORTED) != 0 {
        "AVX-512"
    } else if property(P::NATIVE_RAY8_SUPPORTED) != 0 {
        if cpu_has_avx2() { "AVX2" } else { "AVX" }
    } else if cpu_has_sse42() {
        "SSE4.2"
    } else {
        "SSE2"
    };
    Ok(EmbreeLibrary {
        version: format!("{}.{}.{}", version / 10000, version / 100 % 100, version % 100),
        isa,
    })
}

fn cpu_has_avx2() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::arch::is_x86_feature_detected!("avx2")
            && std::arch::is_x86_feature_detected!("fma")
            && std::arch::is_x86_feature_detected!("bmi2")
    }
    #[cfg(not(target_arch = "x86_64"))]
    false
}

fn cpu_has_sse42() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::arch::is_x86_feature_detected!("sse4.2")
    }
    #[cfg(not(target_arch = "x86_64"))]
    false
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_version_is_the_linked_major_version() {
        let library = library().unwrap();
        let major: u32 = library.version.split('.').next().unwrap().parse().unwrap();
        assert_eq!(major, if cfg!(embree4) { 4 } else { 3 }, "{library}");
        assert_eq!(library.version.split('.').count(), 3, "{library}");
        // The kernels Embree reports for 8-wide packets agree with the CPU's AVX.
        #[cfg(target_arch = "x86_64")]
        assert_eq!(
            matches!(library.isa, "AVX" | "AVX2" | "AVX-512"),
            std::arch::is_x86_feature_detected!("avx"),
            "{library}"
        );
    }
}
