//! Which arbitrary output variables (AOVs) an EXR carries beside the beauty (R, G, B), named
//! as compositing tools and denoisers expect them.

/// The AOVs of an EXR. The default is what embray always wrote: depth and normal.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Aovs {
    /// `Z`: mean distance along the camera ray to the first hit (0 where nothing was hit;
    /// `A` tells those pixels apart).
    pub depth: bool,
    /// `N.X N.Y N.Z`: mean world-space shading normal at the first hit.
    pub normal: bool,
    /// `albedo.R albedo.G albedo.B`: the first hit's reflectance (a denoiser's guide).
    pub albedo: bool,
    /// `variance.R variance.G variance.B`: the sample variance of the pixel's samples
    /// (divide by the spp for the variance of the pixel's value).
    pub variance: bool,
    /// `A`: the fraction of the pixel's samples that hit something.
    pub alpha: bool,
}

impl Default for Aovs {
    fn default() -> Self {
        Aovs { depth: true, normal: true, albedo: false, variance: false, alpha: false }
    }
}

const NAMES: [&str; 5] = ["depth", "normal", "albedo", "variance", "alpha"];

impl Aovs {
    /// A comma list of `depth`, `normal`, `albedo`, `variance`, `alpha`; `none` for only the
    /// beauty.
    pub fn parse(text: &str) -> Result<Aovs, String> {
        let mut aovs =
            Aovs { depth: false, normal: false, albedo: false, variance: false, alpha: false };
        if text.trim() == "none" {
            return Ok(aovs);
        }
        for name in text.split(',').map(str::trim) {
            let flag = match name {
                "depth" => &mut aovs.depth,
                "normal" => &mut aovs.normal,
                "albedo" => &mut aovs.albedo,
                "variance" => &mut aovs.variance,
                "alpha" => &mut aovs.alpha,
                _ => {
                    return Err(format!(
                        "--aovs: '{}' is not an AOV; the AOVs are {} (a comma list), or none",
                        crate::excerpt::excerpt(name),
                        NAMES.join(", ")
                    ));
                }
            };
            *flag = true;
        }
        Ok(aovs)
    }

    fn flags(&self) -> [bool; 5] {
        [self.depth, self.normal, self.albedo, self.variance, self.alpha]
    }
}

impl std::fmt::Display for Aovs {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let chosen: Vec<&str> =
            NAMES.iter().zip(self.flags()).filter(|(_, on)| *on).map(|(n, _)| *n).collect();
        match chosen.is_empty() {
            true => write!(f, "none"),
            false => write!(f, "{}", chosen.join(",")),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Aovs;

    #[test]
    fn lists_parse_and_print_back() {
        for text in
            ["depth,normal", "albedo,variance,alpha", "none", "depth,normal,albedo,variance,alpha"]
        {
            assert_eq!(Aovs::parse(text).unwrap().to_string(), text);
        }
        assert_eq!(Aovs::parse("depth,normal").unwrap(), Aovs::default());
        assert!(Aovs::parse("albedo,colour").unwrap_err().contains("'colour' is not an AOV"));
    }
}
