use rand::{RngExt, SeedableRng};
#[test]
fn scratch() {
    let which = std::env::var("T").unwrap_or("synth".into());
    let n: usize = std::env::var("N")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(2000);
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(
        std::env::var("S")
            .ok()
            .and_then(|s| s.parse().ok())
            .unwrap_or(1),
    );
    if let Ok(f) = std::env::var("F") {
        let data = std::fs::read(f).unwrap();
        rccpack::fuzzing::synth(&data);
        return;
    }
    for i in 0..n {
        let len = rng.random_range(8..400);
        let data: Vec<u8> = (0..len).map(|_| rng.random()).collect();
        std::fs::write(format!("/tmp/cur-{which}"), &data).unwrap();
        let r = std::panic::catch_unwind(|| match which.as_str() {
            "synth" => rccpack::fuzzing::synth(&data),
            "learn" => rccpack::fuzzing::learn(&data),
            "studio" => rccpack::fuzzing::studio(&data),
            _ => unreachable!(),
        });
        if r.is_err() {
            std::fs::write(format!("/tmp/crash-{which}-{i}"), &data).unwrap();
            panic!("crash at {i}");
        }
    }
}
