//! Quick previews of a scene: another resolution (`--resolution`), a window of the image
//! (`--crop`), one camera of several (`--camera`).

use anyhow::{Result, bail};
use embray::film::Tile;
use embray::scene::SceneDesc;
use embray::scene::ceng795::CameraScene;
use std::path::Path;

/// `WxH` → (W, H), each 1 to the largest resolution.
pub fn parse_resolution(text: &str) -> Result<(u32, u32)> {
    let max = embray::limits::MAX_RESOLUTION;
    let parsed = text
        .split_once(['x', 'X'])
        .and_then(|(w, h)| Some((w.trim().parse::<u32>().ok()?, h.trim().parse::<u32>().ok()?)));
    match parsed {
        Some((w, h)) if (1..=max).contains(&w) && (1..=max).contains(&h) => Ok((w, h)),
        _ => bail!("--resolution is '{text}', but must be WIDTHxHEIGHT, each from 1 to {max}"),
    }
}

/// The scene at `width` × `height` pixels with the same view: both fields of view are
/// kept (the pixels stretch if the aspect ratio changes).
pub fn set_resolution(scene: &mut SceneDesc, (width, height): (u32, u32)) {
    let camera = &mut scene.camera;
    let old_aspect = f64::from(camera.width) / f64::from(camera.height);
    let new_aspect = f64::from(width) / f64::from(height);
    camera.pixel_aspect *= old_aspect / new_aspect;
    (camera.width, camera.height) = (width, height);
    scene.settings.crop = None;
}

/// `X0,Y0,X1,Y1` (pixels of the whole image, the second corner excluded) → the window.
pub fn parse_crop(text: &str, (width, height): (u32, u32)) -> Result<Tile> {
    let numbers: Vec<u32> = text.split(',').filter_map(|n| n.trim().parse().ok()).collect();
    match numbers[..] {
        [x0, y0, x1, y1] if x0 < x1 && y0 < y1 && x1 <= width && y1 <= height => {
            Ok(Tile { x0, y0, x1, y1 })
        }
        _ => bail!(
            "--crop is '{text}', but must be X0,Y0,X1,Y1 with X0 < X1 ≤ {width} and Y0 < Y1 ≤ \
             {height} (pixels of the {width}x{height} image; X1 and Y1 are not included)"
        ),
    }
}

/// The cameras `choice` names: an `ImageName` (with or without its extension), or a
/// position in the file counted from 1; all of them without a choice.
pub fn select_cameras(
    cameras: Vec<CameraScene>,
    choice: Option<&str>,
    path: &Path,
) -> Result<Vec<CameraScene>> {
    let Some(choice) = choice else { return Ok(cameras) };
    let stem = |name: &str| Path::new(name).file_stem().map(|s| s.to_string_lossy().into_owned());
    let position = choice.parse::<usize>().ok().filter(|n| (1..=cameras.len()).contains(n));
    let found = cameras
        .iter()
        .position(|c| c.image_name == choice || stem(&c.image_name).as_deref() == Some(choice));
    // A number that is one camera's name and another's position has no right reading.
    if let (Some(named), Some(n)) = (found, position)
        && named != n - 1
    {
        let short = |i: usize| embray::excerpt::excerpt(&cameras[i].image_name);
        let (by_name, by_position) = (short(named), short(n - 1));
        bail!(
            "--camera '{choice}' is ambiguous in '{}': camera {} is named '{by_name}' and camera \
             {n} ('{by_position}') is at position {choice}; give the whole ImageName instead \
             ('{by_name}' or '{by_position}')",
            path.display(),
            named + 1,
        );
    }
    match found.or(position.map(|n| n - 1)) {
        Some(index) => Ok(cameras.into_iter().skip(index).take(1).collect()),
        None => {
            let names: Vec<&str> = cameras.iter().map(|c| c.image_name.as_str()).collect();
            bail!(
                "--camera '{choice}': '{}' has no such camera; it has {} (by ImageName, or 1 to \
                 {})",
                path.display(),
                names.join(", "),
                cameras.len()
            )
        }
    }
}
