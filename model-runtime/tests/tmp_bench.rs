mod common;
use model_runtime::*;
struct Osc12;
static INFO: ModelInfo = common::info("osc12", &[]);
impl Model<12> for Osc12 {
    fn info(&self) -> &'static ModelInfo { &INFO }
    fn rhs(&self, _t: f64, y: &[f64; 12], dy: &mut [f64; 12]) -> Result<(), EvalError> {
        for i in 0..6 { dy[2*i] = y[2*i+1]; dy[2*i+1] = -(1.0 + i as f64) * y[2*i]; }
        Ok(())
    }
}
struct H;
const GS: [GuardSpec<()>; 2] = [GuardSpec { id: (), direction: Direction::Up }, GuardSpec { id: (), direction: Direction::Down }];
impl HybridSystem<12> for H {
    type Mode = (); type Guard = (); type Stop = ();
    fn rhs(&self, _: (), t: f64, y: &[f64; 12], dy: &mut [f64; 12]) -> Result<(), EvalError> { Osc12.rhs(t, y, dy) }
    fn guards(&self, _: ()) -> &[GuardSpec<()>] { &GS }
    fn guard_values(&self, _: (), _t: f64, y: &[f64; 12], dy: &[f64; 12], g: &mut [f64]) -> Result<(), EvalError> { g[0] = y[0] + 0.1 * dy[0]; g[1] = y[2] - 2.0; Ok(()) }
    fn on_event(&mut self, _: (), hit: &EventHit<12, ()>) -> Result<Transition<12, (), ()>, EvalError> { Ok(Transition::Continue { y: hit.y }) }
}
fn go<S: Stepper<12>>(s: S) {
    let mut y0 = [0.0; 12]; for i in 0..6 { y0[2*i] = 1.0; }
    let mut solver = HybridSolver::new(s, Tolerance::scalar(1e-8, 1e-10), HybridOptions::default()).unwrap();
    let t = std::time::Instant::now();
    let out = solver.run(&mut H, (), 0.0, &y0, 3000.0, &mut ()).unwrap();
    let e = t.elapsed();
    println!("{}: {:?} {:?} {:.0} ns/step", S::NAME, out.stats, e, e.as_nanos() as f64 / out.stats.steps as f64);
}
#[test]
fn bench() { go(Dopri5::new()); go(Dop853::new()); go(Rk4::new(0.01)); }
fn plain<S: Stepper<12>>(s: S) {
    let mut y0 = [0.0; 12]; for i in 0..6 { y0[2*i] = 1.0; }
    let t = std::time::Instant::now();
    let out = integrate(&Osc12, s, Tolerance::scalar(1e-8, 1e-10), StepOptions::default(), 0.0, &y0, 3000.0).unwrap();
    let e = t.elapsed();
    println!("plain {}: {:?} {:?} {:.0} ns/step", S::NAME, out.stats, e, e.as_nanos() as f64 / out.stats.steps as f64);
}
#[test]
fn bench_plain() { plain(Dopri5::new()); plain(Dop853::new()); plain(Rk4::new(0.01)); }
