//! Evaluation must not allocate (it runs in the equations-of-motion right-hand side);
//! `allocation_counter::measure` counts the allocations of the current thread.

use karman_math::{
    Cursor, Extrapolation, Function, Interpolation, RegularGrid, ScatteredTable, Table1,
};

#[test]
fn evaluation_does_not_allocate() {
    let tables: Vec<Table1> = [
        Interpolation::Linear,
        Interpolation::Spline,
        Interpolation::Akima,
        Interpolation::Polynomial,
    ]
    .into_iter()
    .map(|i| Table1::sample(f64::cos, 0.0, 3.0, 7, i, Extrapolation::Natural).unwrap())
    .collect();
    let f = Function::table(tables[0].clone()) * Function::table(tables[1].clone())
        + Function::analytic(f64::sin).compose(&Function::table(tables[2].clone()));
    let grid = RegularGrid::new(vec![vec![0.0, 1.0], vec![0.0, 1.0, 2.0]], vec![0.0; 6]).unwrap();
    let scattered = ScatteredTable::new(1, vec![0.0, 1.0], vec![1.0, 2.0], 3.0).unwrap();
    let xs = [0.1, 0.7, 1.3, 2.9, 3.5];
    let mut out = [0.0; 5];
    let mut sum = 0.0;
    let info = allocation_counter::measure(|| {
        let mut cursor = Cursor::default();
        for t in &tables {
            for &x in &xs {
                sum += t.eval(x) + t.eval_with(x, &mut cursor) + t.derivative(x);
                sum += t.second_derivative(x) + t.integral(0.0, x);
            }
        }
        for &x in &xs {
            sum += f.eval(x) + f.derivative(x) + grid.eval(&[x, x]) + scattered.eval(&[x]);
        }
        f.eval_into(&xs, &mut out);
    });
    assert!(sum.is_finite());
    // The counter is live: a Vec allocates.
    let probe = allocation_counter::measure(|| drop(std::hint::black_box(vec![1.0f64; 4])));
    assert!(probe.count_total > 0);
    assert_eq!(
        info.count_total, 0,
        "evaluation allocated {} times",
        info.count_total
    );
}
