use super::testgen::{contact_problem, ContactProblem};
use super::*;
use faer::prelude::*;
use faer::Mat;

struct Rng(u64);
impl Rng {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    fn unif(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
    fn sym(&mut self) -> f64 {
        2.0 * self.unif() - 1.0
    }
}

fn seq_opts() -> SaddleOptions {
    SaddleOptions { par: Par::Seq, ..Default::default() }
}

/// Dense reference via the condensed system:
/// ν_F = H_FF⁻¹ (−c_F − H_FB ν_B), H = E A⁻¹ Eᵀ + D, c = d − E A⁻¹ f, u = A⁻¹ (f − Eᵀ ν).
struct DenseRef {
    h: Mat<f64>,
    ainv_et: Mat<f64>,
    llt: faer::sparse::linalg::solvers::Llt<usize, f64>,
}

impl DenseRef {
    fn new(p: &ContactProblem) -> Self {
        let (n, m) = (p.n, p.m);
        let llt = p.a.sp_cholesky(Side::Lower).unwrap();
        let mut x = Mat::<f64>::zeros(n, m);
        for (r, row) in p.e_rows.iter().enumerate() {
            for &(c, v) in row {
                x[(c, r)] += v;
            }
        }
        llt.solve_in_place(x.as_mut());
        let mut h = Mat::<f64>::zeros(m, m);
        for (r, row) in p.e_rows.iter().enumerate() {
            for j in 0..m {
                h[(r, j)] = row.iter().map(|&(c, v)| v * x[(c, j)]).sum();
            }
        }
        for &(i, j, v) in &p.d {
            h[(i, j)] += v;
        }
        Self { h, ainv_et: x, llt }
    }

    fn solve(&self, p: &ContactProblem, free: &[bool], f: &[f64], d: &[f64], nu_b: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let (n, m) = (p.n, p.m);
        let mut ainv_f = Mat::<f64>::from_fn(n, 1, |i, _| f[i]);
        self.llt.solve_in_place(ainv_f.as_mut());
        let c: Vec<f64> =
            (0..m).map(|r| d[r] - p.e_rows[r].iter().map(|&(col, v)| v * ainv_f[(col, 0)]).sum::<f64>()).collect();
        let fi: Vec<usize> = (0..m).filter(|&j| free[j]).collect();
        let bi: Vec<usize> = (0..m).filter(|&j| !free[j]).collect();
        let mut nu: Vec<f64> = (0..m).map(|j| if free[j] { 0.0 } else { nu_b[j] }).collect();
        if !fi.is_empty() {
            let hff = Mat::<f64>::from_fn(fi.len(), fi.len(), |a, b| self.h[(fi[a], fi[b])]);
            let rhs = Mat::<f64>::from_fn(fi.len(), 1, |a, _| {
                -c[fi[a]] - bi.iter().map(|&b| self.h[(fi[a], b)] * nu_b[b]).sum::<f64>()
            });
            let x = hff.llt(Side::Lower).unwrap().solve(&rhs);
            for (a, &j) in fi.iter().enumerate() {
                nu[j] = x[(a, 0)];
            }
        }
        let u: Vec<f64> =
            (0..n).map(|i| ainv_f[(i, 0)] - (0..m).map(|j| self.ainv_et[(i, j)] * nu[j]).sum::<f64>()).collect();
        (u, nu)
    }
}

/// Relative residuals of the two block equations (natural, unscaled variables).
fn block_residuals(p: &ContactProblem, free: &[bool], f: &[f64], d: &[f64], u: &[f64], nu: &[f64]) -> (f64, f64) {
    let (n, m) = (p.n, p.m);
    // A u + Eᵀ ν − f   (ν includes ν_B: this is the first block with E_Bᵀν_B moved)
    let mut r1 = vec![0.0; n];
    let mut a1 = vec![0.0; n];
    let ar = p.a.as_ref();
    for j in 0..n {
        for (&i, &v) in ar.symbolic().row_idx_of_col_raw(j).iter().zip(ar.val_of_col(j)) {
            r1[i] += v * u[j];
            a1[i] += (v * u[j]).abs();
        }
    }
    for (r, row) in p.e_rows.iter().enumerate() {
        for &(c, v) in row {
            r1[c] += v * nu[r];
            a1[c] += (v * nu[r]).abs();
        }
    }
    let inf = |v: &[f64]| v.iter().fold(0.0f64, |acc, x| acc.max(x.abs()));
    for i in 0..n {
        r1[i] -= f[i];
    }
    let rel1 = inf(&r1) / (inf(&a1) + inf(f));
    // (E u − D ν − d)_F
    let mut dn = vec![0.0; m];
    let mut dabs = vec![0.0; m];
    for &(i, j, v) in &p.d {
        dn[i] += v * nu[j];
        dabs[i] += (v * nu[j]).abs();
    }
    let mut r2 = vec![0.0; m];
    let mut a2 = vec![0.0; m];
    for r in 0..m {
        if free[r] {
            let eu: f64 = p.e_rows[r].iter().map(|&(c, v)| v * u[c]).sum();
            r2[r] = eu - dn[r] - d[r];
            a2[r] = p.e_rows[r].iter().map(|&(c, v)| (v * u[c]).abs()).sum::<f64>() + dabs[r];
        }
    }
    let dfree: Vec<f64> = (0..m).map(|r| if free[r] { d[r] } else { 0.0 }).collect();
    let den2 = inf(&a2) + inf(&dfree);
    let rel2 = if den2 == 0.0 { inf(&r2) } else { inf(&r2) / den2 };
    (rel1, rel2)
}

fn rel_err(a: &[f64], b: &[f64]) -> f64 {
    let num = a.iter().zip(b).fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    let den = b.iter().fold(0.0f64, |m, y| m.max(y.abs()));
    if den == 0.0 {
        num
    } else {
        num / den
    }
}

/// Random partitions (plus all-free and all-fixed), random data, several
/// repeated numeric factorizations on the same symbolic analysis.
fn check_problem(p: &ContactProblem, opts: SaddleOptions, seed: u64, label: &str) {
    let (n, m) = (p.n, p.m);
    let dref = DenseRef::new(p);
    let mut sys = SaddleSystem::with_options(p.a.as_ref(), &p.e_rows, &p.d, opts).unwrap();
    let mut rng = Rng(seed);
    let scale_nu = p.h * 1e-2; // multipliers are tractions ~ stress
    for trial in 0..8 {
        let free: Vec<bool> = match trial {
            0 => vec![true; m],
            1 => vec![false; m],
            _ => {
                let pf = 0.3 + 0.6 * rng.unif();
                (0..m).map(|_| rng.unif() < pf).collect()
            }
        };
        let f: Vec<f64> = (0..n).map(|_| rng.sym() * p.h * p.h).collect();
        let d: Vec<f64> = (0..m).map(|_| rng.sym() * p.h * 1e-3).collect();
        let nu_b: Vec<f64> = (0..m).map(|_| rng.sym() * scale_nu).collect();
        sys.factorize(&free).unwrap();
        let sol = sys.solve(&f, &d, &nu_b).unwrap_or_else(|e| panic!("{label} trial {trial}: {e}"));
        for j in 0..m {
            if !free[j] {
                assert_eq!(sol.nu[j], nu_b[j]);
            }
        }
        let (r1, r2) = block_residuals(p, &free, &f, &d, &sol.u, &sol.nu);
        let (u_ref, nu_ref) = dref.solve(p, &free, &f, &d, &nu_b);
        let (eu, enu) = (rel_err(&sol.u, &u_ref), rel_err(&sol.nu, &nu_ref));
        eprintln!(
            "{label} trial {trial}: nfree {:3}/{m} reg {} steps {} bwd {:.1e} res ({:.1e}, {:.1e}) err u {:.1e} nu {:.1e}",
            free.iter().filter(|&&x| x).count(),
            sys.regularized_pivots(),
            sol.refinement_steps,
            sol.backward_error,
            r1,
            r2,
            eu,
            enu
        );
        assert!(r1 < 1e-10 && r2 < 1e-10, "{label} trial {trial}: residuals {r1:e} {r2:e}");
        assert!(eu < 1e-8 && enu < 1e-8, "{label} trial {trial}: errors {eu:e} {enu:e}");
    }
}

#[test]
fn d_positive_definite_random_partitions() {
    let p = contact_problem(20, 10, true);
    check_problem(&p, seq_opts(), 1, "D>0 cAMD");
    check_problem(&p, SaddleOptions { ordering: SaddleOrdering::Amd, ..seq_opts() }, 2, "D>0 AMD");
}

#[test]
fn d_zero_random_partitions() {
    let p = contact_problem(20, 10, false);
    check_problem(&p, seq_opts(), 3, "D=0 cAMD");
    check_problem(&p, SaddleOptions { ordering: SaddleOrdering::Amd, ..seq_opts() }, 4, "D=0 AMD");
}

#[test]
fn both_factorization_kinds_and_parallel() {
    for (with_d, seed) in [(true, 5), (false, 6)] {
        let p = contact_problem(24, 8, with_d);
        for thr in [SupernodalThreshold::FORCE_SUPERNODAL, SupernodalThreshold::FORCE_SIMPLICIAL] {
            for ordering in [SaddleOrdering::ConstrainedAmd, SaddleOrdering::Amd] {
                let opts =
                    SaddleOptions { supernodal_threshold: thr, ordering, par: Par::rayon(2), ..Default::default() };
                let sys = SaddleSystem::with_options(p.a.as_ref(), &p.e_rows, &p.d, opts).unwrap();
                assert_eq!(sys.is_supernodal(), thr == SupernodalThreshold::FORCE_SUPERNODAL);
                check_problem(&p, opts, seed, &format!("D>0={with_d} {thr:?} {ordering:?}"));
            }
        }
    }
}

#[test]
fn constrained_ordering_needs_no_regularization_for_d_zero() {
    let p = contact_problem(30, 10, false);
    let mut sys = SaddleSystem::with_options(p.a.as_ref(), &p.e_rows, &p.d, seq_opts()).unwrap();
    sys.factorize(&vec![true; p.m]).unwrap();
    assert_eq!(sys.regularized_pivots(), 0);
    // without any regularization the factorization must still exist
    let opts = SaddleOptions { reg_delta: 0.0, reg_eps: 0.0, ..seq_opts() };
    let mut sys = SaddleSystem::with_options(p.a.as_ref(), &p.e_rows, &p.d, opts).unwrap();
    let mut rng = Rng(7);
    let free: Vec<bool> = (0..p.m).map(|_| rng.unif() < 0.5).collect();
    sys.factorize(&free).unwrap();
    let sol = sys.solve(&vec![1e-3; p.n], &vec![1e-4; p.m], &vec![0.0; p.m]).unwrap();
    assert!(sol.refinement_steps <= 2);
}

#[test]
fn plain_amd_without_regularization_fails_cleanly_for_d_zero() {
    let p = contact_problem(20, 10, false);
    let opts = SaddleOptions { ordering: SaddleOrdering::Amd, reg_delta: 0.0, reg_eps: 0.0, ..seq_opts() };
    let mut sys = SaddleSystem::with_options(p.a.as_ref(), &p.e_rows, &p.d, opts).unwrap();
    // AMD eliminates some low-degree multiplier before its displacements: zero pivot
    match sys.factorize(&vec![true; p.m]) {
        Err(SaddleError::ZeroPivot { .. }) => {}
        other => panic!("expected ZeroPivot, got {other:?}"),
    }
    assert_eq!(sys.solve(&vec![0.0; p.n], &vec![0.0; p.m], &vec![0.0; p.m]).unwrap_err(), SaddleError::NotFactorized);
}

#[test]
fn rank_deficient_e_is_reported() {
    // duplicate a row of E with D = 0: E_F rank deficient, K singular
    let mut p = contact_problem(10, 5, false);
    let dup = p.e_rows[4].clone();
    p.e_rows.push(dup);
    p.m += 1;
    let mut sys = SaddleSystem::with_options(p.a.as_ref(), &p.e_rows, &p.d, seq_opts()).unwrap();
    let mut rng = Rng(9);
    let d: Vec<f64> = (0..p.m).map(|_| rng.sym()).collect();
    let res = sys.factorize(&vec![true; p.m]).and_then(|_| sys.solve(&vec![1.0; p.n], &d, &vec![0.0; p.m]));
    match res {
        Err(SaddleError::RefinementNotConverged { .. }) | Err(SaddleError::ZeroPivot { .. }) => {}
        other => panic!("expected an error, got {other:?}"),
    }
    // fixing one of the duplicates makes it regular again
    let mut free = vec![true; p.m];
    free[4] = false;
    sys.factorize(&free).unwrap();
    sys.solve(&vec![1.0; p.n], &d, &vec![0.0; p.m]).unwrap();
}

#[test]
fn invalid_inputs() {
    let p = contact_problem(6, 3, true);
    let mut bad_e = p.e_rows.clone();
    bad_e[0].push((p.n, 1.0));
    assert!(matches!(SaddleSystem::new(p.a.as_ref(), &bad_e, &p.d), Err(SaddleError::InvalidInput(_))));
    let mut bad_d = p.d.clone();
    bad_d.push((0, 1, 1.0));
    assert!(matches!(SaddleSystem::new(p.a.as_ref(), &p.e_rows, &bad_d), Err(SaddleError::InvalidInput(_))));
    let mut sys = SaddleSystem::new(p.a.as_ref(), &p.e_rows, &p.d).unwrap();
    assert_eq!(sys.solve(&vec![0.0; p.n], &vec![0.0; p.m], &vec![0.0; p.m]).unwrap_err(), SaddleError::NotFactorized);
    assert!(matches!(sys.factorize(&[true]), Err(SaddleError::InvalidInput(_))));
    sys.factorize(&vec![true; p.m]).unwrap();
    assert!(matches!(sys.solve(&[0.0], &vec![0.0; p.m], &vec![0.0; p.m]), Err(SaddleError::InvalidInput(_))));
    // unsorted E rows with duplicate columns are merged
    let mut e2 = p.e_rows.clone();
    for row in e2.iter_mut() {
        let (c, v) = row[0];
        row[0].1 = 0.5 * v;
        row.push((c, 0.5 * v));
        row.reverse();
    }
    let mut sys2 = SaddleSystem::new(p.a.as_ref(), &e2, &p.d).unwrap();
    sys2.factorize(&vec![true; p.m]).unwrap();
    let f: Vec<f64> = (0..p.n).map(|i| (i as f64).sin()).collect();
    let a = sys.solve(&f, &vec![0.0; p.m], &vec![0.0; p.m]).unwrap();
    let b = sys2.solve(&f, &vec![0.0; p.m], &vec![0.0; p.m]).unwrap();
    assert!(rel_err(&a.nu, &b.nu) < 1e-10);
}

#[test]
fn unsorted_a_columns_are_accepted() {
    let p = contact_problem(8, 4, false);
    let ar = p.a.as_ref();
    let n = p.n;
    let mut col_ptr = vec![0usize];
    let mut rows = Vec::new();
    let mut vals = Vec::new();
    for j in 0..n {
        let r: Vec<usize> = ar.symbolic().row_idx_of_col_raw(j).to_vec();
        let v: Vec<f64> = ar.val_of_col(j).to_vec();
        rows.extend(r.iter().rev());
        vals.extend(v.iter().rev());
        col_ptr.push(rows.len());
    }
    let a2 = SparseColMat::new(SymbolicSparseColMat::new_unsorted_checked(n, n, col_ptr, None, rows), vals);
    let mut s1 = SaddleSystem::with_options(p.a.as_ref(), &p.e_rows, &p.d, seq_opts()).unwrap();
    let mut s2 = SaddleSystem::with_options(a2.as_ref(), &p.e_rows, &p.d, seq_opts()).unwrap();
    let free: Vec<bool> = (0..p.m).map(|j| j % 3 != 0).collect();
    s1.factorize(&free).unwrap();
    s2.factorize(&free).unwrap();
    let f: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).cos() * 1e-3).collect();
    let d: Vec<f64> = (0..p.m).map(|i| (i as f64).sin() * 1e-5).collect();
    let nb = vec![1e-4; p.m];
    let (x1, x2) = (s1.solve(&f, &d, &nb).unwrap(), s2.solve(&f, &d, &nb).unwrap());
    assert!(rel_err(&x2.u, &x1.u) < 1e-12 && rel_err(&x2.nu, &x1.nu) < 1e-12);
}

/// A partition near the factorized one, solved with the bordered factorization, equals the dense
/// reference; so does a later one that reuses the border columns, and the factorized partition itself
/// afterwards (the values of K̃ are restored).
fn check_near(p: &ContactProblem, opts: SaddleOptions, seed: u64, label: &str) {
    let (n, m) = (p.n, p.m);
    let dref = DenseRef::new(p);
    let mut sys = SaddleSystem::with_options(p.a.as_ref(), &p.e_rows, &p.d, opts).unwrap();
    let mut rng = Rng(seed);
    let f: Vec<f64> = (0..n).map(|_| rng.sym() * p.h * p.h).collect();
    let d: Vec<f64> = (0..m).map(|_| rng.sym() * p.h * 1e-3).collect();
    let nu_b: Vec<f64> = (0..m).map(|_| rng.sym() * p.h * 1e-2).collect();
    let reference: Vec<bool> = (0..m).map(|_| rng.unif() < 0.6).collect();
    sys.factorize(&reference).unwrap();
    let mut near = reference.clone();
    for (step, flips) in [1usize, 3, 6, 30, 0].into_iter().enumerate() {
        // flip a few more (neighbours included, so that freed multipliers couple through D)
        let start = (rng.unif() * (m - flips) as f64) as usize;
        for j in start..start + flips {
            near[j] = !near[j];
        }
        if flips == 0 {
            near.clone_from(&reference);
        }
        let before = sys.border.columns_len();
        let sol = sys.solve_near(&near, &f, &d, &nu_b).unwrap_or_else(|e| panic!("{label} step {step}: {e}"));
        let (u_ref, nu_ref) = dref.solve(p, &near, &f, &d, &nu_b);
        let (eu, enu) = (rel_err(&sol.u, &u_ref), rel_err(&sol.nu, &nu_ref));
        let (r1, r2) = block_residuals(p, &near, &f, &d, &sol.u, &sol.nu);
        eprintln!(
            "{label} step {step}: changed {} new columns {} refinement {} err u {eu:.1e} nu {enu:.1e}",
            sys.changed(&near).len(),
            sys.border.columns_len() - before,
            sol.refinement_steps
        );
        assert!(r1 < 1e-10 && r2 < 1e-10, "{label} step {step}: residuals {r1:e} {r2:e}");
        assert!(eu < 1e-8 && enu < 1e-8, "{label} step {step}: errors {eu:e} {enu:e}");
        let held = sys.border.columns_len();
        let again = sys.solve_near(&near, &f, &d, &nu_b).unwrap();
        assert_eq!(sys.border.columns_len(), held, "the columns are kept");
        assert!(rel_err(&again.u, &sol.u) < 1e-12);
    }
    // The factorized partition still solves as before.
    let sol = sys.solve(&f, &d, &nu_b).unwrap();
    let (u_ref, _) = dref.solve(p, &reference, &f, &d, &nu_b);
    assert!(rel_err(&sol.u, &u_ref) < 1e-8);
}

#[test]
fn nearby_partitions_solve_with_the_bordered_factorization() {
    for (kind, threshold) in
        [("simplicial", SupernodalThreshold::FORCE_SIMPLICIAL), ("supernodal", SupernodalThreshold::FORCE_SUPERNODAL)]
    {
        let opts = SaddleOptions { supernodal_threshold: threshold, ..seq_opts() };
        let p = contact_problem(20, 10, true);
        let mut sys = SaddleSystem::with_options(p.a.as_ref(), &p.e_rows, &p.d, opts).unwrap();
        sys.factorize(&vec![true; sys.m]).unwrap();
        assert_eq!(sys.is_supernodal(), kind == "supernodal");
        check_near(&p, opts, 11, &format!("D>0 {kind}"));
        check_near(&contact_problem(20, 10, false), opts, 12, &format!("D=0 {kind}"));
    }
}

/// A partition far from the factorized one (every multiplier of a long Γ_C, 80 × 4 elements, changed
/// sides): the border columns would hold more values than the factor, so the bordered solve declines with a typed error, and the system
/// still solves its factorized partition (the values of K̃ restored) and, factorized anew, the far one.
#[test]
fn a_far_partition_is_declined_not_bordered() {
    let p = contact_problem(80, 4, true);
    let (n, m) = (p.n, p.m);
    let dref = DenseRef::new(&p);
    let mut sys = SaddleSystem::with_options(p.a.as_ref(), &p.e_rows, &p.d, seq_opts()).unwrap();
    let mut rng = Rng(21);
    let f: Vec<f64> = (0..n).map(|_| rng.sym() * p.h * p.h).collect();
    let d: Vec<f64> = (0..m).map(|_| rng.sym() * p.h * 1e-3).collect();
    let nu_b: Vec<f64> = (0..m).map(|_| rng.sym() * p.h * 1e-2).collect();
    let reference = vec![false; m];
    sys.factorize(&reference).unwrap();
    let far = vec![true; m];
    assert!(matches!(sys.solve_near(&far, &f, &d, &nu_b), Err(SaddleError::TooLarge(_))));
    let sol = sys.solve(&f, &d, &nu_b).unwrap();
    assert!(rel_err(&sol.u, &dref.solve(&p, &reference, &f, &d, &nu_b).0) < 1e-8);
    sys.factorize(&far).unwrap();
    let sol = sys.solve(&f, &d, &nu_b).unwrap();
    assert!(rel_err(&sol.u, &dref.solve(&p, &far, &f, &d, &nu_b).0) < 1e-8);
}

/// `[H_FF⁻¹]_JJ` from the bordered factorization ([`SaddleSystem::inverse_block`]) equals the block of
/// the dense inverse, for the factorized partition itself and for nearby ones (J holding multipliers
/// free in both partitions and freed ones), with and without D, simplicial and supernodal.
#[test]
fn the_inverse_block_of_a_nearby_partition_matches_the_dense_inverse() -> Result<(), SaddleError> {
    for threshold in [SupernodalThreshold::FORCE_SIMPLICIAL, SupernodalThreshold::FORCE_SUPERNODAL] {
        for with_d in [true, false] {
            let p = contact_problem(20, 10, with_d);
            let (n, m) = (p.n, p.m);
            let dref = DenseRef::new(&p);
            let opts = SaddleOptions { supernodal_threshold: threshold, ..seq_opts() };
            let mut sys = SaddleSystem::with_options(p.a.as_ref(), &p.e_rows, &p.d, opts)?;
            let mut rng = Rng(5);
            let reference: Vec<bool> = (0..m).map(|_| rng.unif() < 0.7).collect();
            sys.factorize(&reference)?;
            let (f, d, nu_b) = (vec![0.0; n], vec![1.0; m], vec![0.0; m]);
            let mut near = reference.clone();
            for flips in [0usize, 2, 5] {
                let start = (rng.unif() * (m - flips) as f64) as usize;
                for j in start..start + flips {
                    near[j] = !near[j];
                }
                sys.solve_near(&near, &f, &d, &nu_b)?;
                let free: Vec<usize> = (0..m).filter(|&j| near[j]).collect();
                // every third free multiplier, and every freed one
                let dofs: Vec<usize> =
                    free.iter().copied().filter(|&j| j % 3 == 0 || (near[j] && !reference[j])).collect();
                let block = sys.inverse_block(&near, &dofs)?;
                let hff = Mat::<f64>::from_fn(free.len(), free.len(), |a, b| dref.h[(free[a], free[b])]);
                let llt = hff.llt(Side::Lower).map_err(|e| SaddleError::InvalidInput(format!("{e:?}")))?;
                let inverse = faer::linalg::solvers::DenseSolveCore::inverse(&llt);
                let mut at = vec![usize::MAX; m];
                for (a, &j) in free.iter().enumerate() {
                    at[j] = a;
                }
                let pos = |j: usize| at[j];
                let r = dofs.len();
                let expected: Vec<f64> = (0..r * r).map(|q| inverse[(pos(dofs[q % r]), pos(dofs[q / r]))]).collect();
                let err = rel_err(&block, &expected);
                let freed = dofs.iter().filter(|&&j| !reference[j]).count();
                assert!(r > 3 && (flips == 0 || freed > 0), "{flips} flips: {r} multipliers, {freed} freed");
                assert!(err < 1e-9, "{flips} flips ({freed} freed of {r}): relative error {err:e}");
            }
            assert!(matches!(sys.inverse_block(&near, &[m]), Err(SaddleError::InvalidInput(_))));
        }
    }
    Ok(())
}

/// The displacement dofs in a given order of A (its own Cholesky factor's, or any permutation) solve the same
/// system as the AMD of `A + EᵀE`, on every partition; a system whose rows couple dofs far apart takes the AMD
/// of `A + EᵀE` whatever order is given; an order that is not a permutation of A's dofs is refused.
#[test]
fn a_given_order_of_a_solves_the_same_system() {
    let p = contact_problem(12, 6, true);
    let symbolic = faer::sparse::linalg::cholesky::factorize_symbolic_cholesky(
        p.a.symbolic(),
        faer::Side::Lower,
        Default::default(),
        Default::default(),
    )
    .unwrap();
    let amd: Vec<usize> = symbolic.perm().map_or_else(|| (0..p.n).collect(), |q| q.arrays().0.to_vec());
    let reversed: Vec<usize> = (0..p.n).rev().collect();
    let mut reference = SaddleSystem::with_options(p.a.as_ref(), &p.e_rows, &p.d, seq_opts()).unwrap();
    let mut rng = Rng(7);
    for order in [&amd, &reversed] {
        let mut sys = SaddleSystem::with_order(p.a.as_ref(), &p.e_rows, &p.d, seq_opts(), Some(order)).unwrap();
        for trial in 0..6 {
            let free: Vec<bool> = (0..p.m).map(|j| trial == 0 || rng.unif() < 0.6 || j == 0).collect();
            let f: Vec<f64> = (0..p.n).map(|_| rng.sym() * p.h * p.h).collect();
            let d: Vec<f64> = (0..p.m).map(|_| rng.sym() * p.h * 1e-3).collect();
            let nu_b: Vec<f64> = (0..p.m).map(|_| rng.sym() * p.h * 1e-2).collect();
            reference.factorize(&free).unwrap();
            sys.factorize(&free).unwrap();
            let (a, b) = (reference.solve(&f, &d, &nu_b).unwrap(), sys.solve(&f, &d, &nu_b).unwrap());
            assert!(rel_err(&a.u, &b.u) < 1e-10 && rel_err(&a.nu, &b.nu) < 1e-10, "trial {trial}");
        }
    }
    // The contact rows of one body couple neighbours along Γ_C: within two steps in A's graph. A row that
    // couples dofs far apart (as two bodies' rows do) is not, and the AMD of A + EᵀE orders such a system.
    assert!(ordering::rows_within_two_steps(p.a.as_ref(), &p.e_rows));
    let mut far = p.e_rows.clone();
    far[0].push((p.n - 1, 1.0));
    far[0].push((0, 1.0));
    assert!(!ordering::rows_within_two_steps(p.a.as_ref(), &far));
    let mut sys = SaddleSystem::with_order(p.a.as_ref(), &far, &p.d, seq_opts(), Some(&reversed)).unwrap();
    let mut own = SaddleSystem::with_options(p.a.as_ref(), &far, &p.d, seq_opts()).unwrap();
    assert_eq!(sys.symbolic.perm().map(|q| q.arrays().0.to_vec()), own.symbolic.perm().map(|q| q.arrays().0.to_vec()));
    let free = vec![true; p.m];
    sys.factorize(&free).unwrap();
    own.factorize(&free).unwrap();
    for bad in [vec![0; p.n], (0..p.n - 1).collect(), (1..=p.n).collect::<Vec<usize>>()] {
        for e in [&p.e_rows, &far] {
            let got = SaddleSystem::with_order(p.a.as_ref(), e, &p.d, seq_opts(), Some(&bad));
            assert!(matches!(got, Err(SaddleError::InvalidInput(_))));
        }
    }
}
