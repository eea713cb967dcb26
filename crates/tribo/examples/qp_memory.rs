//! How much memory does one clarabel solve of a dense QP take? (the memory budget's
//! `tribo::qp::DENSE_BYTES_PER_K2`)
//!
//! A dense frictionless QP over k unknowns, `H_ij = 1 / (1 + |i − j|)² + δ_ij` (a decaying kernel like the
//! Γ_C operator's) and `c` from −1 to 1 (half of the dofs pushed), is set up and solved with each KKT
//! solver. Printed per k: the peak resident set (`VmHWM` of `/proc/self/status`) after set-up and after the
//! solve, less the resident set before the caller's H was formed, in units of 8 k² bytes (k² values). Each
//! run is a fresh process (the peak of the process is read), so the example runs itself once per (k, solver).
//!
//! `cargo run --release -p tribo --example qp_memory [K…]` (Linux; 1000, 2000 and 4000 by default, about
//! 10 seconds).
use std::process::Command;

use tribo::qp::BoxQp;
use tribo::settings::{KktSolver, QpSettings};
use tribo::Choice;

/// `VmHWM` (the peak resident set) and `VmRSS` of this process, in bytes.
fn resident() -> [f64; 2] {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    let field = |name: &str| {
        let line = status.lines().find_map(|l| l.strip_prefix(name)).unwrap_or("0");
        1024.0 * line.split_whitespace().next().and_then(|v| v.parse::<f64>().ok()).unwrap_or(f64::NAN)
    };
    [field("VmHWM:"), field("VmRSS:")]
}

/// One measurement, in this process: the peaks after set-up and after the solve over 8 k² bytes.
fn measure(k: usize, kkt: KktSolver) -> tribo::Result<[f64; 2]> {
    let before = resident()[1];
    let h: Vec<f64> = (0..k * k)
        .map(|n| {
            let (i, j) = (n % k, n / k);
            1.0 / (1.0 + i.abs_diff(j) as f64).powi(2) + if i == j { 1.0 } else { 0.0 }
        })
        .collect();
    let c: Vec<f64> = (0..k).map(|i| -1.0 + 2.0 * i as f64 / k as f64).collect();
    let unit = 8.0 * (k * k) as f64;
    let mut qp = BoxQp::new(&h, &c, k, None, &QpSettings { kkt_solver: kkt, ..QpSettings::default() })?;
    let set_up = (resident()[0] - before) / unit;
    let out = qp.solve();
    let solved = (resident()[0] - before) / unit;
    eprintln!("k = {k}, {kkt}: {:?} in {} iterations", out.status, out.iterations);
    Ok([set_up, solved])
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if let [flag, k, kkt] = args.as_slice() {
        if flag == "--one" {
            let [set_up, solved] = measure(k.parse()?, Choice::parse(kkt)?)?;
            println!("{set_up:.2} {solved:.2}");
            return Ok(());
        }
    }
    let sizes: Vec<usize> = if args.is_empty() {
        vec![1000, 2000, 4000]
    } else {
        args.iter().map(|a| a.parse()).collect::<Result<_, _>>()?
    };
    println!("k, KKT solver, peak after set-up and after the solve less the resident set before, over 8 k² bytes");
    for k in sizes {
        for kkt in ["faer", "qdldl"] {
            let out = Command::new(std::env::current_exe()?).args(["--one", &k.to_string(), kkt]).output()?;
            println!("{k:>6} {kkt:>6} {}", String::from_utf8_lossy(&out.stdout).trim());
        }
    }
    println!("the budget counts {} (tribo::qp::DENSE_BYTES_PER_K2 / 8)", tribo::qp::DENSE_BYTES_PER_K2 / 8.0);
    Ok(())
}
