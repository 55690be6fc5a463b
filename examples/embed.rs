//! The core as a library: learn rules from the bundled demonstrations,
//! place a new problem, print where each object goes. Uses only what
//! `default-features = false` builds:
//!
//! ```text
//! cargo run --no-default-features --example embed
//! ```

use rccpack::task::{self, RunOptions, Task};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let task = Task::load(concat!(env!("CARGO_MANIFEST_DIR"), "/examples/box-packing"))?;
    let mut opts = RunOptions::default();
    // Ten seconds for the whole run, learning included.
    opts.synth.stop = rccpack::stop::Stop::after(std::time::Duration::from_secs(10));
    let outcome = task::run(&task, &opts)?;
    println!("learned {} rules", outcome.rules.rules.len());
    let result = &outcome.placement.result;
    let (Some(layout), Some(evaluation)) = (&result.scene, &result.evaluation) else {
        return Err(format!("no layout: {:?}", result.status).into());
    };
    println!("{:?}, score {:.3}", result.status, evaluation.score);
    for (was, o) in task.problem.objects.iter().zip(&layout.objects) {
        if !was.is_placed() {
            let (x, y) = (o.x.unwrap_or_default(), o.y.unwrap_or_default());
            println!("place {} ({}) at ({x}, {y})", o.id, o.class);
        }
    }
    Ok(())
}
