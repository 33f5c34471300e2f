//! A render split into parts — by tiles or by sample ranges, into any number of parts —
//! merges to the whole render bit for bit, on both backends, with motion blur and depth of
//! field on (the library side; `merge_cli.rs` runs the command line and its refusals).

mod common;

use common::*;
use embray::choice::Choice;
use embray::distributed::{Part, Split};
use embray::render::{TILE_SIZE, prepare_scene, render_part};
use embray::sample_sums::FilmSums;

/// The blurred scene's size: 4×3 tiles, the bottom row cut (12 tiles for up to 7 parts).
const WIDTH: u32 = 4 * TILE_SIZE;
const HEIGHT: u32 = 2 * TILE_SIZE + TILE_SIZE / 2;

/// The bundled motion-blur scene, small, seen through a lens focused on the middle box.
fn blurred_scene() -> embray::scene::SceneDesc {
    let text = std::fs::read_to_string(repo_path("scenes/moving_boxes.toml")).unwrap();
    let lens = "f_number = 2.0\nfocal_length = 0.3\nfocus_distance = 6.0";
    let text = text
        .replace("resolution = [320, 200]", &format!("resolution = [{WIDTH}, {HEIGHT}]\n{lens}"));
    assert!(text.contains("f_number"), "the scene's resolution line moved");
    scene_from_str(&text)
}

#[test]
fn every_split_merges_bit_identically_to_the_whole_render() {
    let scene = blurred_scene();
    for backend in backends() {
        let options = options(&scene, backend, 7);
        let effects = prepare_scene(&scene, &options).unwrap().effects;
        assert!(effects.motion_blur && effects.depth_of_field, "both effects are on");
        let whole = render_part(&scene, &options, Part::WHOLE).unwrap();
        assert_eq!(whole.sums.resolve(), render_ok(&scene, &options).film);
        for split in [Split::Tiles, Split::Samples] {
            for count in [1, 2, 3, 7] {
                let mut merged = FilmSums::new(WIDTH, HEIGHT);
                let mut rays = 0;
                for index in 0..count {
                    let part = render_part(&scene, &options, Part { index, count, split }).unwrap();
                    for (m, p) in merged.pixels.iter_mut().zip(&part.sums.pixels) {
                        *m = m.checked_add(p).unwrap();
                    }
                    rays += part.stats.total_rays();
                }
                let what = format!("{} split into {count} by {split}", backend.name());
                assert_eq!(merged, whole.sums, "{what}: sums");
                assert_eq!(merged.resolve(), whole.sums.resolve(), "{what}: image");
                assert_eq!(rays, whole.stats.total_rays(), "{what}: rays");
            }
        }
    }
}

#[test]
fn sample_ranges_merge_bit_identically_for_every_sampler() {
    let scene = blurred_scene();
    for &sampler in embray::sampling::SamplerKind::ALL {
        let mut options = options(&scene, backends()[0], 5);
        options.sampler = sampler;
        let whole = render_part(&scene, &options, Part::WHOLE).unwrap();
        let mut merged = FilmSums::new(WIDTH, HEIGHT);
        for index in 0..3 {
            let part = Part { index, count: 3, split: Split::Samples };
            let sums = render_part(&scene, &options, part).unwrap().sums;
            for (m, p) in merged.pixels.iter_mut().zip(&sums.pixels) {
                *m = m.checked_add(p).unwrap();
            }
        }
        assert_eq!(merged, whole.sums, "{sampler}");
    }
}

#[test]
fn each_part_renders_only_its_share() {
    let scene = cornell(3 * TILE_SIZE, 2 * TILE_SIZE);
    let options = options(&scene, backends()[0], 6);
    let part = Part { index: 1, count: 3, split: Split::Samples };
    let sums = render_part(&scene, &options, part).unwrap().sums;
    assert!(sums.pixels.iter().all(|p| p.samples == 2), "samples 2..4 of 6");
    let part = Part { index: 1, count: 4, split: Split::Tiles };
    let sums = render_part(&scene, &options, part).unwrap().sums;
    let covered = sums.pixels.iter().filter(|p| p.samples == 6).count();
    let empty = sums.pixels.iter().filter(|p| p.samples == 0).count();
    // 3×2 tiles: tiles 1 and 5 are part 1's.
    let tile_pixels = (TILE_SIZE * TILE_SIZE) as usize;
    assert_eq!((covered, empty), (2 * tile_pixels, 4 * tile_pixels));
}

#[test]
fn splits_that_leave_a_part_without_work_are_refused() {
    let scene = cornell(2 * TILE_SIZE, TILE_SIZE);
    let options = options(&scene, backends()[0], 3);
    let too_many_ranges = Part { index: 0, count: 4, split: Split::Samples };
    let message = render_part(&scene, &options, too_many_ranges).unwrap_err().to_string();
    assert!(message.contains("3 spp cannot be split into 4 sample ranges"), "{message}");
    let too_many_tiles = Part { index: 0, count: 3, split: Split::Tiles };
    let message = render_part(&scene, &options, too_many_tiles).unwrap_err().to_string();
    let expected = format!("2 tiles of {TILE_SIZE}x{TILE_SIZE}, too few for 3 tile parts");
    assert!(message.contains(&expected), "{message}");
}
