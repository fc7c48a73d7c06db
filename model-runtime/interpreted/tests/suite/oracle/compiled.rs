//! The oracle's compiled leg, written by the generator (`ORACLE_BLESS=1 cargo test -p model-interpreted
//! --test suite compiled_leg_is_the_generators` writes it again): the first models of
//! `generate`, compiled by `model!`, and their runs by seed.

use model_macros::model;
use model_runtime::{
    run_switched, Const, Dop853, HybridOptions, SwitchedFailure, SwitchedRun, Tolerance,
};

model! {
mod rnd_0 {
    states { x = (-0.958), v = 1.286 }
    let q = x + (-0.283) * v;
    outputs { o = x + (-0.18) * v^2; }
    mode m0 {
        equations { der(x) = v; der(v) = (-29.154) * x + 0.165 * v + (-7.873) + 0 * sin(t); }
        when m0e0: o == (-0.509) { x = (-0.207); }
    }
    mode m1 {
        equations { der(x) = v; der(v) = (-7.337) * x + (-0.378) * v + (-0.222) + 0 * sin(t); }
        when m1e0: x > 0.711 -> m0;
        when m1e1: t == 0.826 -> m0 { v = (-0.714) * v; }
    }
}
}

model! {
mod rnd_1 {
    states { x = (-0.351), v = (-1.363) }
    let q = x + 0.369 * v;
    outputs { o = x + 0.136 * v^2; }
    mode m0 {
        equations { der(x) = v; der(v) = 1.072 * x + (-0.467) * v + (-1.115) + 0 * sin(t); }
        when m0e0: t < 0.571 { v = (-0.563) * v; }
        when m0e0 accumulates -> m1 { v = 0; }
        when m0e1: q == 0.291 -> stop;
    }
    mode m1 {
        equations { der(x) = v; der(v) = (-27.395) * x + (-0.405) * v + (-7.538) + (-4.521) * sin(t); }
        when m1e0: x == (-0.913) -> m0 { x = 0.196; }
    }
    mode m2 {
        equations { der(x) = v; der(v) = (-21.895) * x + (-0.364) * v + 0.873 + 0 * sin(t); }
        when m2e0: v > 0.724 -> m0;
    }
}
}

model! {
mod rnd_2 {
    states { x = 0.24, v = (-1.953) }
    let q = x + 0.24 * v;
    outputs { o = x + 0.01 * v^2; }
    mode m0 {
        equations { der(x) = v; der(v) = (-10.94) * x + (-0.081) * v + (-3.768) + 0 * sin(t); }
        when m0e0: v == (-0.499) { x = (-0.321); }
    }
    mode m1 {
        equations { der(x) = v; der(v) = (-0.176) * x + (-0.756) * v + (-5.997) + 0 * sin(t); }
        when m1e0: v == (-0.904) { x = (-0.238); }
    }
}
}

model! {
mod rnd_3 {
    states { x = 0.871, v = 0.679 }
    let q = x + 0.088 * v;
    outputs { o = x + 0.128 * v^2; }
    mode m0 {
        equations { der(x) = v; der(v) = (-10.385) * x + (-0.913) * v + (-5.671) + 0 * sin(t); }
        when m0e0: x > (-0.018) { v = (-0.8) * v; }
        when m0e1: q > 0.435 { v = (-0.8) * v; }
        when m0e1 accumulates -> m0 { v = 0; }
    }
}
}

model! {
mod rnd_4 {
    states { x = 0.74, v = (-1.001) }
    let q = x + 0.407 * v;
    outputs { o = x + 0.026 * v^2; }
    mode m0 {
        equations { der(x) = v; der(v) = (-2.508) * x + (-0.41) * v + (-2.108) + 0 * sin(t); }
        when m0e0: x == (-0.636) -> m1 { v = (-0.816) * v; }
    }
    mode m1 {
        equations { der(x) = v; der(v) = (-2.761) * x + (-0.047) * v + 2.157 + 2.615 * sin(t); }
        when m1e0: q == (-0.978) -> stop;
    }
}
}

model! {
mod rnd_5 {
    states { x = 0.958, v = (-1.425) }
    let q = x + 0.262 * v;
    outputs { o = x + (-0.114) * v^2; }
    mode m0 {
        equations { der(x) = v; der(v) = (-22.553) * x + (-0.881) * v + (-6.241) + 0 * sin(t); }
        when m0e0: t < 0.853 { x = (-0.099); }
    }
    mode m1 {
        equations { der(x) = v; der(v) = 0.55 * x + 0.127 * v + 6.622 + 0 * sin(t); }
        when m1e0: t > 0.23 { x = (-0.64); }
        when m1e0 accumulates -> m2 { v = 0; }
        when m1e1: q == (-0.083) { x = (-0.456); }
    }
    mode m2 {
        equations { der(x) = v; der(v) = 1.064 * x + (-0.15) * v + (-2.545) + 0 * sin(t); }
        when m2e0: v < 0.058 -> m1 { x = (-0.068); }
    }
}
}

model! {
mod rnd_6 {
    states { x = 0.768, v = (-1.411) }
    let q = x + (-0.266) * v;
    outputs { o = x + 0.091 * v^2; }
    mode m0 {
        equations { der(x) = v; der(v) = (-28.197) * x + (-0.873) * v + 1.015 + 0 * sin(t); }
        when m0e0: x < (-0.764) -> m1 { v = (-0.381) * v; }
        when m0e1: x > (-0.932) { v = (-0.633) * v; }
        when m0e1 accumulates -> m0 { v = 0; }
    }
    mode m1 {
        equations { der(x) = v; der(v) = (-8.525) * x + (-0.986) * v + (-3.684) + 0 * sin(t); }
        when m1e0: q < 0.828 -> stop;
    }
    mode m2 {
        equations { der(x) = v; der(v) = 0.955 * x + (-0.442) * v + (-7.525) + 1.445 * sin(t); }
        when m2e0: v > (-0.2) -> m1 { x = 0.474; }
        when m2e1: x == (-0.644) { x = (-0.105); }
        when m2e1 accumulates -> m2 { v = 0; }
    }
}
}

model! {
mod rnd_7 {
    states { x = 0.759, v = (-0.695) }
    let q = x + 0.364 * v;
    outputs { o = x + 0.019 * v^2; }
    mode m0 {
        equations { der(x) = v; der(v) = (-1.176) * x + (-0.3) * v + (-0.951) + (-0.32) * sin(t); }
        when m0e0: x == (-0.174) { v = (-0.924) * v; }
    }
}
}

model! {
mod rnd_8 {
    states { x = (-0.995), v = (-0.608) }
    let q = x + 0.473 * v;
    outputs { o = x + (-0.036) * v^2; }
    mode m0 {
        equations { der(x) = v; der(v) = (-7.951) * x + (-0.357) * v + (-8.724) + 0 * sin(t); }
        when m0e0: o < (-0.84) { v = (-0.707) * v; }
        when m0e0 accumulates -> m0 { v = 0; }
        when m0e1: x < (-0.993) -> m1 { x = 0.77; }
    }
    mode m1 {
        equations { der(x) = v; der(v) = (-18.792) * x + (-0.518) * v + 9.899 + (-4.425) * sin(t); }
        when m1e0: t < 1.359 -> m0 { x = (-0.941); }
        when m1e1: t == 0.255 -> stop;
    }
}
}

model! {
mod rnd_9 {
    states { x = 0.05, v = 1.105 }
    let q = x + (-0.393) * v;
    outputs { o = x + 0.168 * v^2; }
    mode m0 {
        equations { der(x) = v; der(v) = (-21.51) * x + (-0.058) * v + (-4.749) + 1.458 * sin(t); }
        when m0e0: x > 0.578 { v = (-0.44) * v; }
        when m0e0 accumulates -> m1 { v = 0; }
    }
    mode m1 {
        equations { der(x) = v; der(v) = (-11.911) * x + (-0.764) * v + 2.142 + 0 * sin(t); }
        when m1e0: q < (-0.063) { x = (-0.056); }
        when m1e1: x > 0.405 -> m0 { v = (-0.301) * v; }
    }
}
}

model! {
mod rnd_10 {
    states { x = (-0.732), v = (-1.605) }
    let q = x + (-0.088) * v;
    outputs { o = x + (-0.012) * v^2; }
    mode m0 {
        equations { der(x) = v; der(v) = (-25.809) * x + 0.01 * v + 7.126 + 0 * sin(t); }
        when m0e0: t == 1.946 -> stop;
    }
    mode m1 {
        equations { der(x) = v; der(v) = (-1.212) * x + (-0.95) * v + (-4.147) + 4.192 * sin(t); }
        when m1e0: x < 0.57 -> m0 { x = 0.928; }
    }
}
}

model! {
mod rnd_11 {
    states { x = 0.518, v = (-0.177) }
    let q = x + (-0.323) * v;
    outputs { o = x + 0.126 * v^2; }
    mode m0 {
        equations { der(x) = v; der(v) = (-9.583) * x + (-0.394) * v + (-6.696) + 0 * sin(t); }
        when m0e0: x == (-0.319) { v = (-0.406) * v; }
        when m0e1: x < (-0.509) { v = (-0.892) * v; }
    }
}
}

model! {
mod rnd_12 {
    states { x = 0.121, v = 1.134 }
    let q = x + 0.492 * v;
    outputs { o = x + (-0.078) * v^2; }
    mode m0 {
        equations { der(x) = v; der(v) = (-22.488) * x + 0.086 * v + 7.043 + (-3.607) * sin(t); }
        when m0e0: t == 0.28 { x = 0.353; }
        when m0e0 accumulates -> m0 { v = 0; }
        when m0e1: t > 1.241 { v = (-0.8) * v; }
    }
}
}

model! {
mod rnd_13 {
    states { x = (-0.876), v = 1.706 }
    let q = x + (-0.041) * v;
    outputs { o = x + 0.042 * v^2; }
    mode m0 {
        equations { der(x) = v; der(v) = (-9.749) * x + (-0.65) * v + 6.332 + 0 * sin(t); }
        when m0e0: t == 0.424 { v = (-0.642) * v; }
        when m0e0 accumulates -> m1 { v = 0; }
        when m0e1: q > 0.99 { v = (-0.8) * v; }
    }
    mode m1 {
        equations { der(x) = v; der(v) = (-10.903) * x + (-0.673) * v + 9.923 + 0 * sin(t); }
        when m1e0: x < (-0.383) { v = (-0.8) * v; }
        when m1e0 accumulates -> m0 { v = 0; }
        when m1e1: t > 1.621 { x = 0.856; }
    }
}
}

model! {
mod rnd_14 {
    states { x = 0.95, v = (-0.357) }
    let q = x + (-0.323) * v;
    outputs { o = x + 0.093 * v^2; }
    mode m0 {
        equations { der(x) = v; der(v) = (-29.522) * x + (-0.208) * v + 8.004 + 0 * sin(t); }
        when m0e0: o == 0.94 { x = (-0.565); }
        when m0e0 accumulates -> m2 { v = 0; }
    }
    mode m1 {
        equations { der(x) = v; der(v) = (-3.393) * x + 0.111 * v + 5.506 + 0 * sin(t); }
        when m1e0: t < 0.937 -> m0;
    }
    mode m2 {
        equations { der(x) = v; der(v) = (-24.482) * x + 0.068 * v + 8.579 + 0 * sin(t); }
        when m2e0: t < 0.284 -> m1 { v = (-0.519) * v; }
    }
}
}

model! {
mod rnd_15 {
    states { x = (-0.572), v = 1.332 }
    let q = x + (-0.184) * v;
    outputs { o = x + 0.068 * v^2; }
    mode m0 {
        equations { der(x) = v; der(v) = (-12.064) * x + (-0.741) * v + (-6.417) + 0 * sin(t); }
        when m0e0: o < (-0.306) -> m1 { x = (-0.651); }
    }
    mode m1 {
        equations { der(x) = v; der(v) = (-18.615) * x + (-0.31) * v + (-2.149) + 0 * sin(t); }
        when m1e0: o < (-0.156) { v = (-0.8) * v; }
    }
    mode m2 {
        equations { der(x) = v; der(v) = (-16.645) * x + (-0.571) * v + (-1.802) + (-3.73) * sin(t); }
        when m2e0: x > 0.419 -> m0 { v = (-0.741) * v; }
        when m2e1: x < 0.029 { v = (-0.382) * v; }
    }
}
}

model! {
mod rnd_16 {
    states { x = (-0.036), v = 0.321 }
    let q = x + (-0.318) * v;
    outputs { o = x + (-0.078) * v^2; }
    mode m0 {
        equations { der(x) = v; der(v) = (-2.85) * x + (-0.291) * v + 2.877 + (-1.263) * sin(t); }
        when m0e0: t < 1.752 { x = 0.272; }
        when m0e1: x == 0.325 -> m1 { x = 0.511; }
    }
    mode m1 {
        equations { der(x) = v; der(v) = (-1.103) * x + 0.027 * v + (-5.83) + 0 * sin(t); }
        when m1e0: x == 0.107 { v = (-0.8) * v; }
        when m1e1: t > 0.946 -> m0 { v = (-0.735) * v; }
    }
    mode m2 {
        equations { der(x) = v; der(v) = (-11.138) * x + (-0.007) * v + (-3.302) + (-1.61) * sin(t); }
        when m2e0: o > (-0.421) { v = (-0.8) * v; }
        when m2e0 accumulates -> m2 { v = 0; }
    }
}
}

model! {
mod rnd_17 {
    states { x = 0.754, v = (-0.36) }
    let q = x + (-0.38) * v;
    outputs { o = x + (-0.063) * v^2; }
    mode m0 {
        equations { der(x) = v; der(v) = (-19.493) * x + (-0.731) * v + (-9.655) + (-4.686) * sin(t); }
        when m0e0: o < 0.418 { v = (-0.8) * v; }
        when m0e0 accumulates -> m0 { v = 0; }
        when m0e1: t == 1.975 { v = (-0.8) * v; }
        when m0e1 accumulates -> m0 { v = 0; }
    }
}
}

model! {
mod rnd_18 {
    states { x = (-0.091), v = 0.633 }
    let q = x + (-0.402) * v;
    outputs { o = x + 0.036 * v^2; }
    mode m0 {
        equations { der(x) = v; der(v) = (-16.223) * x + (-0.156) * v + (-7.578) + 0 * sin(t); }
        when m0e0: x == 0.421 -> stop;
    }
    mode m1 {
        equations { der(x) = v; der(v) = (-29.162) * x + 0.035 * v + (-4.745) + (-3.063) * sin(t); }
        when m1e0: q > 0.226 { v = (-0.603) * v; }
        when m1e0 accumulates -> m0 { v = 0; }
    }
}
}

model! {
mod rnd_19 {
    states { x = 0.495, v = 0.203 }
    let q = x + 0.373 * v;
    outputs { o = x + 0.112 * v^2; }
    mode m0 {
        equations { der(x) = v; der(v) = (-18.365) * x + (-0.901) * v + 5.681 + 0 * sin(t); }
        when m0e0: x > (-0.503) { v = (-0.888) * v; }
    }
}
}

model! {
mod rnd_20 {
    states { x = 0.076, v = (-0.96) }
    let q = x + (-0.453) * v;
    outputs { o = x + (-0.116) * v^2; }
    mode m0 {
        equations { der(x) = v; der(v) = (-21.941) * x + (-0.566) * v + (-7.95) + 3.272 * sin(t); }
        when m0e0: x < (-0.301) { v = (-0.8) * v; }
        when m0e0 accumulates -> m0 { v = 0; }
        when m0e1: t < 0.06 -> stop;
    }
}
}

model! {
mod rnd_21 {
    states { x = (-0.859), v = (-0.321) }
    let q = x + 0.018 * v;
    outputs { o = x + (-0.138) * v^2; }
    mode m0 {
        equations { der(x) = v; der(v) = (-13.201) * x + (-0.219) * v + (-8.198) + 0 * sin(t); }
        when m0e0: v == (-0.283) -> m1 { x = 0.522; }
        when m0e1: x > (-0.014) -> m1 { x = 0.59; }
    }
    mode m1 {
        equations { der(x) = v; der(v) = (-16.938) * x + (-0.768) * v + (-6.829) + 0 * sin(t); }
        when m1e0: x < 0.737 -> m0 { v = (-0.473) * v; }
    }
}
}

model! {
mod rnd_22 {
    states { x = (-0.25), v = (-0.162) }
    let q = x + 0.177 * v;
    outputs { o = x + 0.062 * v^2; }
    mode m0 {
        equations { der(x) = v; der(v) = (-27.55) * x + (-0.193) * v + 6.652 + 0 * sin(t); }
        when m0e0: v == 0.418 { v = (-0.8) * v; }
    }
    mode m1 {
        equations { der(x) = v; der(v) = (-5.229) * x + (-0.885) * v + (-6.584) + (-2.941) * sin(t); }
        when m1e0: x == 0.76 -> m0;
    }
    mode m2 {
        equations { der(x) = v; der(v) = (-21.386) * x + (-0.01) * v + (-5.05) + 0 * sin(t); }
        when m2e0: x == (-0.363) { x = 0.658; }
        when m2e0 accumulates -> m0 { v = 0; }
    }
}
}

model! {
mod rnd_23 {
    states { x = 0.213, v = (-0.738) }
    let q = x + (-0.227) * v;
    outputs { o = x + 0.182 * v^2; }
    mode m0 {
        equations { der(x) = v; der(v) = (-29.466) * x + 0.108 * v + 5.192 + 0 * sin(t); }
        when m0e0: v > 0.044 -> m1 { x = 0.122; }
        when m0e1: x < 0.916 { v = (-0.637) * v; }
        when m0e1 accumulates -> m0 { v = 0; }
    }
    mode m1 {
        equations { der(x) = v; der(v) = (-28.883) * x + (-0.39) * v + 1.574 + 0 * sin(t); }
        when m1e0: v == (-0.56) -> m0;
        when m1e1: v == (-0.091) { v = (-0.376) * v; }
        when m1e1 accumulates -> m0 { v = 0; }
    }
}
}

model! {
mod rnd_24 {
    states { x = (-0.452), v = (-1.179) }
    let q = x + (-0.03) * v;
    outputs { o = x + 0.193 * v^2; }
    mode m0 {
        equations { der(x) = v; der(v) = (-29.107) * x + (-0.321) * v + 6.916 + 0 * sin(t); }
        when m0e0: x == 0.042 -> stop;
        when m0e1: v < 0.553 { v = (-0.8) * v; }
        when m0e1 accumulates -> m0 { v = 0; }
    }
}
}

model! {
mod rnd_25 {
    states { x = 0.534, v = (-1.61) }
    let q = x + 0.399 * v;
    outputs { o = x + (-0.017) * v^2; }
    mode m0 {
        equations { der(x) = v; der(v) = 1.483 * x + (-0.448) * v + (-6.045) + (-0.384) * sin(t); }
        when m0e0: v == 0.409 { v = (-0.8) * v; }
        when m0e0 accumulates -> m0 { v = 0; }
    }
}
}

model! {
mod rnd_26 {
    states { x = 0.985, v = 0.636 }
    let q = x + (-0.468) * v;
    outputs { o = x + 0.061 * v^2; }
    mode m0 {
        equations { der(x) = v; der(v) = (-20.942) * x + (-0.609) * v + 9.116 + (-4.057) * sin(t); }
        when m0e0: x < (-0.322) { v = (-0.528) * v; }
        when m0e0 accumulates -> m0 { v = 0; }
        when m0e1: x < (-0.683) { x = 0.687; }
    }
    mode m1 {
        equations { der(x) = v; der(v) = (-29.56) * x + (-0.644) * v + 5.369 + 0 * sin(t); }
        when m1e0: x == (-0.931) -> m0 { x = 0.729; }
    }
}
}

model! {
mod rnd_27 {
    states { x = 0.306, v = (-0.408) }
    let q = x + (-0.482) * v;
    outputs { o = x + 0.005 * v^2; }
    mode m0 {
        equations { der(x) = v; der(v) = (-26.845) * x + (-0.211) * v + (-0.348) + 1.22 * sin(t); }
        when m0e0: v > 0.266 { v = (-0.8) * v; }
    }
    mode m1 {
        equations { der(x) = v; der(v) = (-10.948) * x + (-0.826) * v + (-2.916) + (-0.582) * sin(t); }
        when m1e0: t > 0.922 -> stop;
        when m1e1: x > 0.397 -> stop;
    }
}
}

model! {
mod rnd_28 {
    states { x = (-0.387), v = (-0.768) }
    let q = x + 0.187 * v;
    outputs { o = x + 0.091 * v^2; }
    mode m0 {
        equations { der(x) = v; der(v) = (-6.457) * x + (-0.451) * v + 0.73 + 0 * sin(t); }
        when m0e0: x < 0.639 -> m1;
    }
    mode m1 {
        equations { der(x) = v; der(v) = (-18.774) * x + (-0.911) * v + (-9.673) + (-3.696) * sin(t); }
        when m1e0: q > (-0.921) { v = (-0.792) * v; }
    }
}
}

model! {
mod rnd_29 {
    states { x = (-0.903), v = (-1.081) }
    let q = x + (-0.397) * v;
    outputs { o = x + (-0.173) * v^2; }
    mode m0 {
        equations { der(x) = v; der(v) = (-1.784) * x + (-0.61) * v + (-8.412) + 0 * sin(t); }
        when m0e0: q == 0.829 { v = (-0.8) * v; }
    }
    mode m1 {
        equations { der(x) = v; der(v) = (-11.368) * x + (-0.81) * v + (-8.295) + 0 * sin(t); }
        when m1e0: t < 1.067 { v = (-0.342) * v; }
    }
    mode m2 {
        equations { der(x) = v; der(v) = (-20.033) * x + (-0.215) * v + 5.888 + 0 * sin(t); }
        when m2e0: q == 0.342 -> m0 { x = 0.35; }
        when m2e1: v > 0.376 -> m0 { v = (-0.677) * v; }
    }
}
}

model! {
mod rnd_30 {
    states { x = (-0.744), v = 1.088 }
    let q = x + 0.01 * v;
    outputs { o = x + (-0.172) * v^2; }
    mode m0 {
        equations { der(x) = v; der(v) = (-7.047) * x + (-0.62) * v + 7.892 + 0 * sin(t); }
        when m0e0: q == (-0.837) -> m1 { x = (-0.378); }
    }
    mode m1 {
        equations { der(x) = v; der(v) = (-25.134) * x + 0.157 * v + 9.8 + 0 * sin(t); }
        when m1e0: x == (-0.46) { x = (-0.417); }
        when m1e1: x > 0.262 -> m0 { v = (-0.52) * v; }
    }
    mode m2 {
        equations { der(x) = v; der(v) = (-20.283) * x + (-0.066) * v + 7.2 + 0 * sin(t); }
        when m2e0: x == (-0.394) -> m0;
        when m2e1: v == (-0.448) -> m0 { v = (-0.513) * v; }
    }
}
}

model! {
mod rnd_31 {
    states { x = (-0.6), v = (-1.392) }
    let q = x + (-0.323) * v;
    outputs { o = x + (-0.062) * v^2; }
    mode m0 {
        equations { der(x) = v; der(v) = (-13.845) * x + (-0.351) * v + 1.932 + 0 * sin(t); }
        when m0e0: x < (-0.451) { v = (-0.8) * v; }
        when m0e0 accumulates -> m0 { v = 0; }
    }
}
}

model! {
mod rnd_32 {
    states { x = 0.215, v = (-0.443) }
    let q = x + (-0.036) * v;
    outputs { o = x + (-0.068) * v^2; }
    mode m0 {
        equations { der(x) = v; der(v) = (-20.889) * x + (-0.138) * v + 1.279 + 0 * sin(t); }
        when m0e0: v > 0.265 { v = (-0.8) * v; }
    }
    mode m1 {
        equations { der(x) = v; der(v) = (-28.641) * x + (-0.174) * v + 1.064 + 0 * sin(t); }
        when m1e0: t == 1.287 -> m0 { v = (-0.619) * v; }
        when m1e1: o == (-0.36) -> m0;
    }
}
}

model! {
mod rnd_33 {
    states { x = 0.077, v = 0.8 }
    let q = x + 0.237 * v;
    outputs { o = x + (-0.136) * v^2; }
    mode m0 {
        equations { der(x) = v; der(v) = (-20.459) * x + (-0.809) * v + 3.75 + (-2.489) * sin(t); }
        when m0e0: o > 0.738 { x = 0.124; }
    }
}
}

model! {
mod rnd_34 {
    states { x = (-0.324), v = 1.082 }
    let q = x + 0.267 * v;
    outputs { o = x + (-0.134) * v^2; }
    mode m0 {
        equations { der(x) = v; der(v) = (-15.511) * x + (-0.329) * v + (-6.161) + 0 * sin(t); }
        when m0e0: t > 0.175 { v = (-0.8) * v; }
        when m0e0 accumulates -> m0 { v = 0; }
        when m0e1: x < 0.945 { v = (-0.8) * v; }
    }
    mode m1 {
        equations { der(x) = v; der(v) = (-22.535) * x + (-0.086) * v + 2.422 + 0 * sin(t); }
        when m1e0: x == (-0.151) -> m2;
    }
    mode m2 {
        equations { der(x) = v; der(v) = (-5.7) * x + (-0.68) * v + (-4.897) + 0 * sin(t); }
        when m2e0: q == (-0.337) -> m1 { x = (-0.244); }
        when m2e1: t < 1.836 -> m0 { x = (-0.141); }
    }
}
}

model! {
mod rnd_35 {
    states { x = 0.837, v = 0.016 }
    let q = x + 0.144 * v;
    outputs { o = x + 0.003 * v^2; }
    mode m0 {
        equations { der(x) = v; der(v) = (-4.328) * x + (-0.563) * v + 5.151 + (-0.271) * sin(t); }
        when m0e0: o < 0.232 { v = (-0.8) * v; }
    }
}
}

model! {
mod rnd_36 {
    states { x = (-0.891), v = (-1.586) }
    let q = x + (-0.113) * v;
    outputs { o = x + (-0.142) * v^2; }
    mode m0 {
        equations { der(x) = v; der(v) = (-20.548) * x + (-0.58) * v + 1.561 + 0 * sin(t); }
        when m0e0: v > 0.646 { x = 0.508; }
        when m0e1: t == 0.773 { v = (-0.8) * v; }
        when m0e1 accumulates -> m0 { v = 0; }
    }
    mode m1 {
        equations { der(x) = v; der(v) = (-3.507) * x + (-0.967) * v + (-4.039) + 0 * sin(t); }
        when m1e0: v == 0.06 -> m2 { v = (-0.355) * v; }
    }
    mode m2 {
        equations { der(x) = v; der(v) = (-15.142) * x + (-0.124) * v + (-5.559) + 4.917 * sin(t); }
        when m2e0: t < 1.734 { v = (-0.923) * v; }
        when m2e1: x > 0.141 { v = (-0.715) * v; }
    }
}
}

model! {
mod rnd_37 {
    states { x = (-0.726), v = 1.198 }
    let q = x + (-0.176) * v;
    outputs { o = x + (-0.011) * v^2; }
    mode m0 {
        equations { der(x) = v; der(v) = (-6.723) * x + (-0.965) * v + (-5.653) + 1.478 * sin(t); }
        when m0e0: o > (-0.151) -> stop;
    }
    mode m1 {
        equations { der(x) = v; der(v) = 0.566 * x + (-0.525) * v + (-1.876) + 3.679 * sin(t); }
        when m1e0: q == (-0.549) -> m0 { x = (-0.386); }
    }
    mode m2 {
        equations { der(x) = v; der(v) = (-6.781) * x + 0.01 * v + (-3.475) + 2.056 * sin(t); }
        when m2e0: x > (-0.54) -> m0;
    }
}
}

model! {
mod rnd_38 {
    states { x = (-0.535), v = 1.152 }
    let q = x + (-0.283) * v;
    outputs { o = x + 0.076 * v^2; }
    mode m0 {
        equations { der(x) = v; der(v) = (-27.464) * x + (-0.735) * v + (-3.452) + 0 * sin(t); }
        when m0e0: o == (-0.085) { x = (-0.161); }
    }
}
}

model! {
mod rnd_39 {
    states { x = (-0.471), v = 1.761 }
    let q = x + (-0.134) * v;
    outputs { o = x + 0.092 * v^2; }
    mode m0 {
        equations { der(x) = v; der(v) = (-18.055) * x + (-0.241) * v + 5.902 + 0 * sin(t); }
        when m0e0: x < (-0.502) -> m1 { v = (-0.834) * v; }
    }
    mode m1 {
        equations { der(x) = v; der(v) = (-6.69) * x + (-0.513) * v + 2.394 + 0 * sin(t); }
        when m1e0: x == 0.974 -> m0 { x = (-0.588); }
        when m1e1: v > (-0.85) { v = (-0.8) * v; }
    }
    mode m2 {
        equations { der(x) = v; der(v) = (-19.047) * x + (-0.521) * v + (-6.659) + 0 * sin(t); }
        when m2e0: x == (-0.723) { v = (-0.746) * v; }
    }
}
}

/// The compiled run of the model of `seed` to `t_end` at rtol 1e-11, atol 1e-13 (`None`: not compiled).
pub fn run(
    seed: u64,
    t_end: f64,
) -> Option<Result<SwitchedRun<Const<2>>, SwitchedFailure<Const<2>>>> {
    macro_rules! go {
        ($m:ident) => {
            Some(run_switched(
                $m::Model::default(),
                Dop853::new(),
                Tolerance::scalar(1e-11, 1e-13),
                HybridOptions::default(),
                (0.0, $m::INITIAL),
                t_end,
            ))
        };
    }
    match seed {
        0 => go!(rnd_0),
        1 => go!(rnd_1),
        2 => go!(rnd_2),
        3 => go!(rnd_3),
        4 => go!(rnd_4),
        5 => go!(rnd_5),
        6 => go!(rnd_6),
        7 => go!(rnd_7),
        8 => go!(rnd_8),
        9 => go!(rnd_9),
        10 => go!(rnd_10),
        11 => go!(rnd_11),
        12 => go!(rnd_12),
        13 => go!(rnd_13),
        14 => go!(rnd_14),
        15 => go!(rnd_15),
        16 => go!(rnd_16),
        17 => go!(rnd_17),
        18 => go!(rnd_18),
        19 => go!(rnd_19),
        20 => go!(rnd_20),
        21 => go!(rnd_21),
        22 => go!(rnd_22),
        23 => go!(rnd_23),
        24 => go!(rnd_24),
        25 => go!(rnd_25),
        26 => go!(rnd_26),
        27 => go!(rnd_27),
        28 => go!(rnd_28),
        29 => go!(rnd_29),
        30 => go!(rnd_30),
        31 => go!(rnd_31),
        32 => go!(rnd_32),
        33 => go!(rnd_33),
        34 => go!(rnd_34),
        35 => go!(rnd_35),
        36 => go!(rnd_36),
        37 => go!(rnd_37),
        38 => go!(rnd_38),
        39 => go!(rnd_39),
        _ => None,
    }
}
