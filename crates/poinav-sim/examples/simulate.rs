//! Runs a scenario file (every variant) and writes its outputs: the command-line stand-in until
//! `poinav simulate` is wired. `cargo run -p poinav-sim --example simulate -- SCENARIO OUT_DIR`

use std::path::Path;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let (file, out) = match args.as_slice() {
        [_, f, o] => (f, o),
        _ => return Err("usage: simulate SCENARIO OUT_DIR".into()),
    };
    let scenario = poinav_sim::Scenario::load(Path::new(file))?;
    let variants: Vec<Option<String>> = if scenario.variants.is_empty() {
        vec![None]
    } else {
        scenario
            .variants
            .iter()
            .map(|v| Some(v.name.clone()))
            .collect()
    };
    let mut all = true;
    for v in variants {
        let building = poinav_bridge::prepare(&scenario, v.as_deref())?;
        let outcome = poinav_sim::run(&scenario, v.as_deref(), building.floor())?;
        let dir = match &v {
            Some(v) => Path::new(out).join(v),
            None => Path::new(out).to_path_buf(),
        };
        poinav_sim::write_outputs(&dir, &outcome, building.floor())?;
        for j in &outcome.judged {
            println!(
                "{} line {} {}: {} -> {}",
                v.as_deref().unwrap_or("-"),
                j.line,
                j.kind,
                if j.pass { "PASS" } else { "FAIL" },
                j.measured
            );
        }
        all &= outcome.passed();
    }
    std::process::exit(if all { 0 } else { 1 });
}
