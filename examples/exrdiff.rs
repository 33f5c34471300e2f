fn main() {
    let args: Vec<String> = std::env::args().collect();
    let read = |p: &str| {
        exr::prelude::read_all_flat_layers_from_file(p)
            .unwrap()
            .layer_data
            .into_iter()
            .next()
            .unwrap()
            .channel_data
            .list
            .into_iter()
            .map(|c| {
                (
                    c.name.to_string(),
                    match c.sample_data {
                        exr::prelude::FlatSamples::F32(v) => {
                            v.iter().map(|x| x.to_bits()).collect::<Vec<u32>>()
                        }
                        _ => vec![],
                    },
                )
            })
            .collect::<Vec<_>>()
    };
    let (a, b) = (read(&args[1]), read(&args[2]));
    println!("{}", if a == b { "IDENTICAL" } else { "DIFFERENT" });
}
