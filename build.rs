//! Finds Embree and generates its bindings when the `embree` feature is on.
//!
//! Search order: `EMBREE_DIR`, then `pkg-config embree4|embree3` (Debian ships no .pc for
//! Embree 3, so this mostly helps custom installs), then `/usr/include/embree4|embree3`.
//! With `embree4-sys` the bindings and the `-lembree4` come from that crate; we set the cfg
//! and, when `EMBREE_DIR` names a prefix (e.g. the one `scripts/embree4-runtime.sh` makes),
//! its library path and rpath.

fn main() {
    // Declared unconditionally so `cfg(embree4)` never warns, whatever the features.
    println!("cargo::rustc-check-cfg=cfg(embree4)");
    println!("cargo::rustc-check-cfg=cfg(course_data)");
    println!("cargo::rustc-check-cfg=cfg(mitsuba_data)");
    println!("cargo:rerun-if-changed=build.rs");
    // The CENG795 packs beside the checkout (CI has them): tests that compare with the
    // instructor's images run when they are there and are reported as ignored otherwise.
    let course_data = std::path::Path::new("../shared/data/ceng795");
    println!("cargo:rerun-if-changed={}", course_data.display());
    if course_data.is_dir() {
        println!("cargo:rustc-cfg=course_data");
    }
    // Mitsuba 3's render regression suite and scenes, the same way.
    let mitsuba_data = std::path::Path::new("../shared/data/mitsuba");
    println!("cargo:rerun-if-changed={}", mitsuba_data.display());
    if mitsuba_data.is_dir() {
        println!("cargo:rustc-cfg=mitsuba_data");
    }
    // The oidn crate links OIDN_DIR/lib (scripts/oidn-runtime.sh makes it); an rpath lets the
    // binaries find it there without LD_LIBRARY_PATH.
    if std::env::var_os("CARGO_FEATURE_DENOISE").is_some() {
        println!("cargo:rerun-if-env-changed=OIDN_DIR");
        match std::env::var_os("OIDN_DIR") {
            Some(dir) => {
                let lib = std::path::Path::new(&dir).join("lib");
                println!("cargo:rustc-link-arg=-Wl,-rpath,{}", lib.display());
            }
            None => println!(
                "cargo:warning=the denoise feature needs OIDN_DIR: \
                 export OIDN_DIR=$(bash scripts/oidn-runtime.sh)"
            ),
        }
    }
    // Cargo compiles this script with `feature = "embree"` exactly when it sets
    // CARGO_FEATURE_EMBREE; the cfg is needed anyway, since bindgen is only a build
    // dependency with that feature.
    #[cfg(feature = "embree")]
    if std::env::var_os("CARGO_FEATURE_EMBREE4_SYS").is_some() {
        println!("cargo:rustc-cfg=embree4");
        embree::link_embree_dir();
    } else {
        embree::generate();
    }
}

#[cfg(feature = "embree")]
mod embree {
    use std::env;
    use std::path::{Path, PathBuf};
    use std::process::Command;

    const NOT_FOUND: &str = "Embree not found (looked in EMBREE_DIR, pkg-config, \
        /usr/include/embree4, /usr/include/embree3). On Debian/Ubuntu: \
        sudo apt-get install libembree-dev libclang-dev — or build without Embree: \
        cargo build --no-default-features --features obvhs";

    const NO_LIBCLANG: &str = "bindgen could not load libclang, which it needs to read \
        the Embree headers. On Debian/Ubuntu: sudo apt-get install libclang-dev (or set \
        LIBCLANG_PATH) — or build without Embree: \
        cargo build --no-default-features --features obvhs";

    /// An Embree installation: `include_dir/embree{major}/rtcore.h`, libraries in `lib_dirs`.
    struct Install {
        major: u32,
        include_dir: PathBuf,
        lib_dirs: Vec<PathBuf>,
    }

    impl Install {
        fn header(&self) -> PathBuf {
            self.include_dir.join(format!("embree{}", self.major)).join("rtcore.h")
        }
    }

    pub fn generate() {
        println!("cargo:rerun-if-env-changed=EMBREE_DIR");
        println!("cargo:rerun-if-env-changed=PKG_CONFIG_PATH");
        println!("cargo:rerun-if-env-changed=LIBCLANG_PATH");
        let install = find().unwrap_or_else(|msg| fail(&msg));
        let header = install.header();
        println!("cargo:rerun-if-changed={}", header.display());

        if install.major == 4 {
            println!("cargo:rustc-cfg=embree4");
        }
        link_search(&install.lib_dirs);
        println!("cargo:rustc-link-lib=embree{}", install.major);

        let source = bindings(&install);
        let out = PathBuf::from(env::var("OUT_DIR").expect("cargo sets OUT_DIR"));
        let path = out.join("embree_bindings.rs");
        std::fs::write(&path, source)
            .unwrap_or_else(|e| fail(&format!("cannot write {}: {e}", path.display())));
    }

    /// For `embree4-sys`, which links `embree4` from the default paths: `EMBREE_DIR`'s
    /// libraries go first when it is set.
    pub fn link_embree_dir() {
        println!("cargo:rerun-if-env-changed=EMBREE_DIR");
        if let Some(dir) = env::var_os("EMBREE_DIR") {
            link_search(&lib_dirs(Path::new(&dir)));
        }
    }

    fn lib_dirs(prefix: &Path) -> Vec<PathBuf> {
        ["lib", "lib64"].iter().map(|l| prefix.join(l)).filter(|d| d.is_dir()).collect()
    }

    fn link_search(dirs: &[PathBuf]) {
        for dir in dirs {
            println!("cargo:rustc-link-search=native={}", dir.display());
            // Custom installs are not on the loader path; without this the binary and the
            // tests would build and then fail to start.
            if cfg!(unix) {
                println!("cargo:rustc-link-arg=-Wl,-rpath,{}", dir.display());
            }
        }
    }

    /// Stops the build with `msg` as cargo's one top-level error. A panic (or a nonzero
    /// exit) would bury it under "failed to run custom build command", the script's whole
    /// output and, with RUST_BACKTRACE set, a backtrace. `cargo::error` fails the build by
    /// itself (Cargo >= 1.84, below our rust-version), hence the exit status 0.
    fn fail(msg: &str) -> ! {
        println!("cargo::error={msg}");
        std::process::exit(0);
    }

    fn find() -> Result<Install, String> {
        if let Some(dir) = env::var_os("EMBREE_DIR") {
            let dir = PathBuf::from(dir);
            let include_dir = dir.join("include");
            let lib_dirs = lib_dirs(&dir);
            for major in [4, 3] {
                let install =
                    Install { major, include_dir: include_dir.clone(), lib_dirs: lib_dirs.clone() };
                if install.header().is_file() {
                    return Ok(install);
                }
            }
            return Err(format!(
                "EMBREE_DIR={} contains neither include/embree4/rtcore.h nor \
                 include/embree3/rtcore.h. Point EMBREE_DIR at an Embree install prefix, or \
                 unset it to use the system Embree (Debian/Ubuntu: sudo apt-get install \
                 libembree-dev libclang-dev), or build without Embree: \
                 cargo build --no-default-features --features obvhs",
                dir.display()
            ));
        }
        for major in [4, 3] {
            if let Some(install) = pkg_config(major) {
                return Ok(install);
            }
        }
        for major in [4, 3] {
            let install =
                Install { major, include_dir: PathBuf::from("/usr/include"), lib_dirs: Vec::new() };
            if install.header().is_file() {
                return Ok(install);
            }
        }
        Err(NOT_FOUND.to_string())
    }

    /// Asks the `pkg-config` binary, if there is one, about `embree{major}`.
    fn pkg_config(major: u32) -> Option<Install> {
        let name = format!("embree{major}");
        let var = |v: &str| -> Option<String> {
            let out = Command::new("pkg-config")
                .arg(format!("--variable={v}"))
                .arg(&name)
                .output()
                .ok()?;
            let s = String::from_utf8(out.stdout).ok()?.trim().to_string();
            (out.status.success() && !s.is_empty()).then_some(s)
        };
        let include_dir = PathBuf::from(var("includedir")?);
        let lib_dirs = var("libdir").map(PathBuf::from).into_iter().collect();
        let install = Install { major, include_dir, lib_dirs };
        install.header().is_file().then_some(install)
    }

    fn bindings(install: &Install) -> String {
        let header = install.header();
        let include_arg = format!("-I{}", install.include_dir.display());
        // bindgen panics (rather than returning an error) when libclang cannot be loaded;
        // catch that so the user sees one message saying what to install.
        let previous_hook = std::panic::take_hook();
        std::panic::set_hook(Box::new(|_| {}));
        let result = std::panic::catch_unwind(|| builder(&header, &include_arg).generate());
        std::panic::set_hook(previous_hook);
        let generated = match result {
            Ok(Ok(b)) => b.to_string(),
            Ok(Err(e)) => fail(&format!(
                "bindgen failed on {}: {e}. Is the Embree header complete? \
                 Reinstall libembree-dev, or build without Embree: \
                 cargo build --no-default-features --features obvhs",
                header.display()
            )),
            Err(_) => fail(NO_LIBCLANG),
        };
        rename_like_embree4_sys(&generated)
    }

    /// The same settings as the `embree4-sys` crate, so names match between the two sources.
    fn builder(header: &Path, include_arg: &str) -> bindgen::Builder {
        bindgen::Builder::default()
            .header(header.display().to_string())
            .clang_arg(include_arg)
            .parse_callbacks(Box::new(bindgen::CargoCallbacks::new()))
            .allowlist_function("rtc.*")
            .allowlist_type("RTC.*")
            .allowlist_var("RTC.*")
            .rustified_enum("RTCFormat")
            .rustified_enum("RTCBuildQuality")
            .rustified_enum("RTCDeviceProperty")
            .rustified_enum("RTCError")
            .rustified_enum("RTCBufferType")
            .rustified_enum("RTCGeometryType")
            .rustified_enum("RTCSubdivisionMode")
            .bitfield_enum("RTC.*Flags")
            .blocklist_type("RTCPointQueryN")
    }

    fn rename_like_embree4_sys(source: &str) -> String {
        const PREFIXES: [&str; 11] = [
            "RTC_FORMAT_",
            "RTC_BUILD_QUALITY_",
            "RTC_RAY_QUERY_FLAG_",
            "RTC_DEVICE_PROPERTY_",
            "RTC_ERROR_",
            "RTC_BUFFER_TYPE_",
            "RTC_GEOMETRY_TYPE_",
            "RTC_SUBDIVISION_MODE_",
            "RTC_CURVE_FLAG_",
            "RTC_SCENE_FLAG_",
            "RTC_BUILD_FLAG_",
        ];
        PREFIXES.iter().fold(source.to_string(), |s, p| s.replace(p, ""))
    }
}
