//! Inputs that grow by naming or nesting rather than by their size: a chain of blends that
//! each name one material twice (2^n materials from n lines), `<include>`s that fan out,
//! tags nested 200,000 deep, a `<ref>` that leads back to its own BSDF. Each is refused in
//! well under a second, with its file and line, before it takes the time, memory or stack
//! it asks for.

use crate::harness::{Scratch, refused_in, scene};
use std::time::{Duration, Instant};

/// `refused_in`, which must also be quick: the cases below would take minutes or all the
/// memory if they were read as they ask.
#[track_caller]
fn refused_quickly(scratch: &Scratch, args: &[&str], expected: &[&str]) {
    let start = Instant::now();
    refused_in(scratch, args, expected);
    assert!(start.elapsed() < Duration::from_secs(10), "took {:?}", start.elapsed());
}

/// A Mitsuba scene of a sphere with the BSDF `bsdf` (by reference), after `before`.
fn xml_with(before: &str, bsdf: &str) -> String {
    format!(
        "<scene version=\"3.0.0\">\n{before}\n<shape type=\"sphere\"><ref id=\"{bsdf}\"/></shape>\n\
         <emitter type=\"constant\"/>\n</scene>\n"
    )
}

#[test]
fn a_toml_chain_of_blends_naming_one_material_twice_stops_at_the_limit() {
    let mut blends = String::new();
    for k in 1..=60 {
        let next = if k == 60 { "grey".to_owned() } else { format!("m{}", k + 1) };
        blends += &format!(
            "[materials.m{k}]\ntype = \"blend\"\nmaterials = [\"{next}\", \"{next}\"]\nweight = 0.5\n"
        );
    }
    let scratch = Scratch::new();
    scratch.write("s.toml", scene(&blends));
    // The first blend over 64 materials: m55, with 2^7 - 1 = 127.
    let expected = ["s.toml", "materials.m55.materials", "127 materials", "at most 64", "line"];
    refused_quickly(&scratch, &["render", "s.toml"], &expected);
    refused_quickly(&scratch, &["info", "s.toml"], &expected);
}

#[test]
fn a_toml_chain_of_blends_deeper_than_the_limit_is_refused_before_its_end() {
    // 100,000 links, each a blend of the next and one plain material: read to its end, the
    // recursion would overflow the stack.
    let mut blends = String::new();
    for k in 0..100_000 {
        blends += &format!(
            "[materials.m{k}]\ntype = \"blend\"\nmaterials = [\"m{}\", \"grey\"]\nweight = 0.5\n",
            k + 1
        );
    }
    blends += "[materials.m100000]\nalbedo = [0.5, 0.5, 0.5]\n";
    let scratch = Scratch::new();
    scratch.write("s.toml", scene(&blends));
    refused_quickly(&scratch, &["info", "s.toml"], &["s.toml", "blends nested 64 deep", "line"]);
}

#[test]
fn a_mitsuba_chain_of_blends_naming_one_bsdf_twice_stops_at_the_limit() {
    let mut bsdfs = String::from("<bsdf type=\"diffuse\" id=\"m30\"/>\n");
    for k in (1..30).rev() {
        let next = k + 1;
        bsdfs += &format!(
            "<bsdf type=\"blendbsdf\" id=\"m{k}\"><float name=\"weight\" value=\"0.5\"/>\
             <ref id=\"m{next}\"/><ref id=\"m{next}\"/></bsdf>\n"
        );
    }
    let scratch = Scratch::new();
    scratch.write("s.xml", xml_with(&bsdfs, "m1"));
    let expected = ["s.xml", "id=\"m24\"", "127 materials in one blendbsdf", "(at most 64)"];
    refused_quickly(&scratch, &["info", "s.xml"], &expected);
}

#[test]
fn a_mitsuba_ref_that_leads_back_to_its_own_bsdf_is_refused() {
    let scratch = Scratch::new();
    let own = "<bsdf type=\"twosided\" id=\"a\"><ref id=\"a\"/></bsdf>";
    scratch.write("own.xml", xml_with(own, "a"));
    let expected = ["own.xml", "id=\"a\"", "BSDFs nest deeper than 64", "line 2"];
    refused_quickly(&scratch, &["info", "own.xml"], &expected);
    // Through another BSDF.
    let pair = "<bsdf type=\"blendbsdf\" id=\"a\"><float name=\"weight\" value=\"0.5\"/>\
                <ref id=\"b\"/><bsdf type=\"diffuse\"/></bsdf>\n\
                <bsdf type=\"mask\" id=\"b\"><ref id=\"a\"/></bsdf>";
    scratch.write("pair.xml", xml_with(pair, "a"));
    refused_quickly(&scratch, &["info", "pair.xml"], &["pair.xml", "BSDFs nest deeper than 64"]);
}

#[test]
fn mitsuba_tags_nested_200000_deep_are_refused() {
    let depth = 200_000;
    let text = format!(
        "<scene version=\"3.0.0\"><shape type=\"sphere\">{}<bsdf type=\"diffuse\"/>{}</shape></scene>\n",
        "<bsdf type=\"twosided\">".repeat(depth),
        "</bsdf>".repeat(depth)
    );
    let scratch = Scratch::new();
    scratch.write("s.xml", text);
    let expected = ["s.xml", "<bsdf type=\"twosided\">", "elements nest deeper than 100", "line 1"];
    refused_quickly(&scratch, &["info", "s.xml"], &expected);
}

#[test]
fn mitsuba_includes_that_fan_out_are_refused_at_the_limit() {
    // a0.xml includes a1.xml four times, … a15.xml holds one sphere: 4^15 spheres.
    let scratch = Scratch::new();
    for k in 0..15 {
        let include = format!("<include filename=\"a{}.xml\"/>\n", k + 1);
        scratch.write(
            &format!("a{k}.xml"),
            format!("<scene version=\"3.0.0\">\n{}</scene>\n", include.repeat(4)),
        );
    }
    scratch.write("a15.xml", "<scene version=\"3.0.0\"><shape type=\"sphere\"/></scene>\n");
    let expected = ["<include>", "the scene reads more than 10000 includes"];
    refused_quickly(&scratch, &["info", "a0.xml"], &expected);
}

#[test]
fn a_mitsuba_property_given_twice_is_refused_as_mitsuba_refuses_it() {
    let sensor = "<sensor type=\"perspective\"><float name=\"fov\" value=\"40\"/>\
                  <float name=\"fov\" value=\"90\"/></sensor>\n<bsdf type=\"diffuse\" id=\"d\"/>";
    let shape = "<bsdf type=\"diffuse\" id=\"d\"/>\n<shape type=\"rectangle\">\
                 <transform name=\"to_world\"><scale value=\"2\"/></transform>\n\
                 <transform name=\"to_world\"><translate x=\"1\"/></transform><ref id=\"d\"/></shape>";
    let scratch = Scratch::new();
    for (file, before, property, line) in
        [("fov.xml", sensor, "fov", "line 2"), ("to_world.xml", shape, "to_world", "line 4")]
    {
        scratch.write(file, xml_with(before, "d"));
        let twice = format!("the property `{property}` is given twice");
        refused_in(&scratch, &["info", file], &[file, &twice, line]);
    }
}

/// A property in an included file and beside the `<include>` is given twice too: Mitsuba
/// reads both into one plugin's properties.
#[test]
fn a_property_given_again_by_an_include_is_refused() {
    let scratch = Scratch::new();
    scratch.write(
        "radius.xml",
        "<scene version=\"3.0.0\"><float name=\"radius\" value=\"2\"/></scene>\n",
    );
    let shape = "<bsdf type=\"diffuse\" id=\"d\"/>\n<shape type=\"sphere\" id=\"s\">\
                 <float name=\"radius\" value=\"1\"/>\n<include filename=\"radius.xml\"/><ref id=\"d\"/></shape>";
    scratch.write("s.xml", format!("<scene version=\"3.0.0\">\n{shape}\n</scene>\n"));
    refused_in(
        &scratch,
        &["info", "s.xml"],
        &["radius.xml", "the property `radius` is given twice", "line 1"],
    );
}

/// Defaults made of defaults double at each: 2^40 bytes from 40 lines, refused at 1 MiB.
#[test]
fn defaults_that_double_at_each_are_refused() {
    let mut defaults = String::from("<default name=\"a0\" value=\"xx\"/>\n");
    for k in 1..40 {
        defaults += &format!("<default name=\"a{k}\" value=\"$a{}$a{}\"/>\n", k - 1, k - 1);
    }
    let scratch = Scratch::new();
    scratch.write("s.xml", xml_with(&defaults, "a"));
    let expected = ["s.xml", "a value grows past 1048576 bytes as $names are replaced"];
    refused_quickly(&scratch, &["info", "s.xml"], &expected);
}

/// The nesting bound is the whole scene's: includes do not start it again.
#[test]
fn nesting_through_includes_is_bounded_too() {
    let scratch = Scratch::new();
    let (open, close) = ("<bsdf type=\"twosided\">".repeat(60), "</bsdf>".repeat(60));
    for k in 0..3 {
        let inner = format!("{open}<include filename=\"n{}.xml\"/>{close}", k + 1);
        scratch.write(&format!("n{k}.xml"), format!("<scene version=\"3.0.0\">{inner}</scene>\n"));
    }
    scratch.write("n3.xml", "<scene version=\"3.0.0\"><bsdf type=\"diffuse\"/></scene>\n");
    refused_quickly(&scratch, &["info", "n0.xml"], &["n1.xml", "elements nest deeper than 100"]);
}
