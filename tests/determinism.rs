//! Same scene and seed → bit-identical image for any thread count.

mod common;

use common::*;
use embray::choice::Choice;
use embray::render::TILE_SIZE;

#[test]
fn one_and_two_threads_give_bit_identical_images() {
    // 3×2 tiles, the right and bottom ones cut: more tiles than threads.
    let scene = cornell(TILE_SIZE * 5 / 2, TILE_SIZE * 3 / 2);
    for backend in backends() {
        let mut one = options(&scene, backend, 3);
        one.threads = Some(1);
        let mut two = one.clone();
        two.threads = Some(2);
        let a = render_ok(&scene, &one);
        let b = render_ok(&scene, &two);
        assert_eq!(a.film, b.film, "{}", backend.name());
        assert_eq!(a.stats, b.stats, "{}", backend.name());
    }
}

#[test]
fn different_seeds_give_different_noise() {
    let scene = cornell(16, 16);
    let backend = backends()[0];
    let a = render_ok(&scene, &options(&scene, backend, 1));
    let mut other = options(&scene, backend, 1);
    other.seed = 8;
    let b = render_ok(&scene, &other);
    assert_ne!(a.film.color, b.film.color);
}
