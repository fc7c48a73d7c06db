// A chain of 20 equal pendulum links (point masses m at the ends of massless rods of length l,
// hanging from a fixed pivot): 40 states, one dense 20 x 20 block of accelerations solved
// numerically at run time. Link i (1 = at the pivot) carries the masses i..20, so with
// c_ij = 21 - max(i, j) Lagrange's equations are
//   sum_j c_ij cos(q_i - q_j) der(w_j) = -sum_j c_ij sin(q_i - q_j) w_j^2 - (g / l) c_ii sin(q_i)
// (in units of m l^2), and the energy m l^2 (1/2 sum_ij c_ij cos(q_i - q_j) w_i w_j
// - (g / l) sum_i c_ii cos(q_i)) is conserved. `eulerdisk model solve` runs it unpadded.
/// Twenty pendulum links in a chain; `q_i` the angle of link `i` from the downward vertical.
pub mod pendulum_chain {
    params { m = 1, l = 1, g = 9.81 }
    states { q1, q2, q3, q4, q5, q6, q7, q8, q9, q10, q11, q12, q13, q14, q15, q16, q17, q18, q19, q20, w1, w2, w3, w4, w5, w6, w7, w8, w9, w10, w11, w12, w13, w14, w15, w16, w17, w18, w19, w20 }
    options { swell_bound = 0 }
    equations {
        der(q1) = w1;
        der(q2) = w2;
        der(q3) = w3;
        der(q4) = w4;
        der(q5) = w5;
        der(q6) = w6;
        der(q7) = w7;
        der(q8) = w8;
        der(q9) = w9;
        der(q10) = w10;
        der(q11) = w11;
        der(q12) = w12;
        der(q13) = w13;
        der(q14) = w14;
        der(q15) = w15;
        der(q16) = w16;
        der(q17) = w17;
        der(q18) = w18;
        der(q19) = w19;
        der(q20) = w20;
        link1: 20 * der(w1)
            + 19 * cos(q1 - q2) * der(w2)
            + 18 * cos(q1 - q3) * der(w3)
            + 17 * cos(q1 - q4) * der(w4)
            + 16 * cos(q1 - q5) * der(w5)
            + 15 * cos(q1 - q6) * der(w6)
            + 14 * cos(q1 - q7) * der(w7)
            + 13 * cos(q1 - q8) * der(w8)
            + 12 * cos(q1 - q9) * der(w9)
            + 11 * cos(q1 - q10) * der(w10)
            + 10 * cos(q1 - q11) * der(w11)
            + 9 * cos(q1 - q12) * der(w12)
            + 8 * cos(q1 - q13) * der(w13)
            + 7 * cos(q1 - q14) * der(w14)
            + 6 * cos(q1 - q15) * der(w15)
            + 5 * cos(q1 - q16) * der(w16)
            + 4 * cos(q1 - q17) * der(w17)
            + 3 * cos(q1 - q18) * der(w18)
            + 2 * cos(q1 - q19) * der(w19)
            + 1 * cos(q1 - q20) * der(w20)
            = -19 * sin(q1 - q2) * w2^2
            - 18 * sin(q1 - q3) * w3^2
            - 17 * sin(q1 - q4) * w4^2
            - 16 * sin(q1 - q5) * w5^2
            - 15 * sin(q1 - q6) * w6^2
            - 14 * sin(q1 - q7) * w7^2
            - 13 * sin(q1 - q8) * w8^2
            - 12 * sin(q1 - q9) * w9^2
            - 11 * sin(q1 - q10) * w10^2
            - 10 * sin(q1 - q11) * w11^2
            - 9 * sin(q1 - q12) * w12^2
            - 8 * sin(q1 - q13) * w13^2
            - 7 * sin(q1 - q14) * w14^2
            - 6 * sin(q1 - q15) * w15^2
            - 5 * sin(q1 - q16) * w16^2
            - 4 * sin(q1 - q17) * w17^2
            - 3 * sin(q1 - q18) * w18^2
            - 2 * sin(q1 - q19) * w19^2
            - 1 * sin(q1 - q20) * w20^2
            - g / l * 20 * sin(q1);
        link2: 19 * cos(q2 - q1) * der(w1)
            + 19 * der(w2)
            + 18 * cos(q2 - q3) * der(w3)
            + 17 * cos(q2 - q4) * der(w4)
            + 16 * cos(q2 - q5) * der(w5)
            + 15 * cos(q2 - q6) * der(w6)
            + 14 * cos(q2 - q7) * der(w7)
            + 13 * cos(q2 - q8) * der(w8)
            + 12 * cos(q2 - q9) * der(w9)
            + 11 * cos(q2 - q10) * der(w10)
            + 10 * cos(q2 - q11) * der(w11)
            + 9 * cos(q2 - q12) * der(w12)
            + 8 * cos(q2 - q13) * der(w13)
            + 7 * cos(q2 - q14) * der(w14)
            + 6 * cos(q2 - q15) * der(w15)
            + 5 * cos(q2 - q16) * der(w16)
            + 4 * cos(q2 - q17) * der(w17)
            + 3 * cos(q2 - q18) * der(w18)
            + 2 * cos(q2 - q19) * der(w19)
            + 1 * cos(q2 - q20) * der(w20)
            = -19 * sin(q2 - q1) * w1^2
            - 18 * sin(q2 - q3) * w3^2
            - 17 * sin(q2 - q4) * w4^2
            - 16 * sin(q2 - q5) * w5^2
            - 15 * sin(q2 - q6) * w6^2
            - 14 * sin(q2 - q7) * w7^2
            - 13 * sin(q2 - q8) * w8^2
            - 12 * sin(q2 - q9) * w9^2
            - 11 * sin(q2 - q10) * w10^2
            - 10 * sin(q2 - q11) * w11^2
            - 9 * sin(q2 - q12) * w12^2
            - 8 * sin(q2 - q13) * w13^2
            - 7 * sin(q2 - q14) * w14^2
            - 6 * sin(q2 - q15) * w15^2
            - 5 * sin(q2 - q16) * w16^2
            - 4 * sin(q2 - q17) * w17^2
            - 3 * sin(q2 - q18) * w18^2
            - 2 * sin(q2 - q19) * w19^2
            - 1 * sin(q2 - q20) * w20^2
            - g / l * 19 * sin(q2);
        link3: 18 * cos(q3 - q1) * der(w1)
            + 18 * cos(q3 - q2) * der(w2)
            + 18 * der(w3)
            + 17 * cos(q3 - q4) * der(w4)
            + 16 * cos(q3 - q5) * der(w5)
            + 15 * cos(q3 - q6) * der(w6)
            + 14 * cos(q3 - q7) * der(w7)
            + 13 * cos(q3 - q8) * der(w8)
            + 12 * cos(q3 - q9) * der(w9)
            + 11 * cos(q3 - q10) * der(w10)
            + 10 * cos(q3 - q11) * der(w11)
            + 9 * cos(q3 - q12) * der(w12)
            + 8 * cos(q3 - q13) * der(w13)
            + 7 * cos(q3 - q14) * der(w14)
            + 6 * cos(q3 - q15) * der(w15)
            + 5 * cos(q3 - q16) * der(w16)
            + 4 * cos(q3 - q17) * der(w17)
            + 3 * cos(q3 - q18) * der(w18)
            + 2 * cos(q3 - q19) * der(w19)
            + 1 * cos(q3 - q20) * der(w20)
            = -18 * sin(q3 - q1) * w1^2
            - 18 * sin(q3 - q2) * w2^2
            - 17 * sin(q3 - q4) * w4^2
            - 16 * sin(q3 - q5) * w5^2
            - 15 * sin(q3 - q6) * w6^2
            - 14 * sin(q3 - q7) * w7^2
            - 13 * sin(q3 - q8) * w8^2
            - 12 * sin(q3 - q9) * w9^2
            - 11 * sin(q3 - q10) * w10^2
            - 10 * sin(q3 - q11) * w11^2
            - 9 * sin(q3 - q12) * w12^2
            - 8 * sin(q3 - q13) * w13^2
            - 7 * sin(q3 - q14) * w14^2
            - 6 * sin(q3 - q15) * w15^2
            - 5 * sin(q3 - q16) * w16^2
            - 4 * sin(q3 - q17) * w17^2
            - 3 * sin(q3 - q18) * w18^2
            - 2 * sin(q3 - q19) * w19^2
            - 1 * sin(q3 - q20) * w20^2
            - g / l * 18 * sin(q3);
        link4: 17 * cos(q4 - q1) * der(w1)
            + 17 * cos(q4 - q2) * der(w2)
            + 17 * cos(q4 - q3) * der(w3)
            + 17 * der(w4)
            + 16 * cos(q4 - q5) * der(w5)
            + 15 * cos(q4 - q6) * der(w6)
            + 14 * cos(q4 - q7) * der(w7)
            + 13 * cos(q4 - q8) * der(w8)
            + 12 * cos(q4 - q9) * der(w9)
            + 11 * cos(q4 - q10) * der(w10)
            + 10 * cos(q4 - q11) * der(w11)
            + 9 * cos(q4 - q12) * der(w12)
            + 8 * cos(q4 - q13) * der(w13)
            + 7 * cos(q4 - q14) * der(w14)
            + 6 * cos(q4 - q15) * der(w15)
            + 5 * cos(q4 - q16) * der(w16)
            + 4 * cos(q4 - q17) * der(w17)
            + 3 * cos(q4 - q18) * der(w18)
            + 2 * cos(q4 - q19) * der(w19)
            + 1 * cos(q4 - q20) * der(w20)
            = -17 * sin(q4 - q1) * w1^2
            - 17 * sin(q4 - q2) * w2^2
            - 17 * sin(q4 - q3) * w3^2
            - 16 * sin(q4 - q5) * w5^2
            - 15 * sin(q4 - q6) * w6^2
            - 14 * sin(q4 - q7) * w7^2
            - 13 * sin(q4 - q8) * w8^2
            - 12 * sin(q4 - q9) * w9^2
            - 11 * sin(q4 - q10) * w10^2
            - 10 * sin(q4 - q11) * w11^2
            - 9 * sin(q4 - q12) * w12^2
            - 8 * sin(q4 - q13) * w13^2
            - 7 * sin(q4 - q14) * w14^2
            - 6 * sin(q4 - q15) * w15^2
            - 5 * sin(q4 - q16) * w16^2
            - 4 * sin(q4 - q17) * w17^2
            - 3 * sin(q4 - q18) * w18^2
            - 2 * sin(q4 - q19) * w19^2
            - 1 * sin(q4 - q20) * w20^2
            - g / l * 17 * sin(q4);
        link5: 16 * cos(q5 - q1) * der(w1)
            + 16 * cos(q5 - q2) * der(w2)
            + 16 * cos(q5 - q3) * der(w3)
            + 16 * cos(q5 - q4) * der(w4)
            + 16 * der(w5)
            + 15 * cos(q5 - q6) * der(w6)
            + 14 * cos(q5 - q7) * der(w7)
            + 13 * cos(q5 - q8) * der(w8)
            + 12 * cos(q5 - q9) * der(w9)
            + 11 * cos(q5 - q10) * der(w10)
            + 10 * cos(q5 - q11) * der(w11)
            + 9 * cos(q5 - q12) * der(w12)
            + 8 * cos(q5 - q13) * der(w13)
            + 7 * cos(q5 - q14) * der(w14)
            + 6 * cos(q5 - q15) * der(w15)
            + 5 * cos(q5 - q16) * der(w16)
            + 4 * cos(q5 - q17) * der(w17)
            + 3 * cos(q5 - q18) * der(w18)
            + 2 * cos(q5 - q19) * der(w19)
            + 1 * cos(q5 - q20) * der(w20)
            = -16 * sin(q5 - q1) * w1^2
            - 16 * sin(q5 - q2) * w2^2
            - 16 * sin(q5 - q3) * w3^2
            - 16 * sin(q5 - q4) * w4^2
            - 15 * sin(q5 - q6) * w6^2
            - 14 * sin(q5 - q7) * w7^2
            - 13 * sin(q5 - q8) * w8^2
            - 12 * sin(q5 - q9) * w9^2
            - 11 * sin(q5 - q10) * w10^2
            - 10 * sin(q5 - q11) * w11^2
            - 9 * sin(q5 - q12) * w12^2
            - 8 * sin(q5 - q13) * w13^2
            - 7 * sin(q5 - q14) * w14^2
            - 6 * sin(q5 - q15) * w15^2
            - 5 * sin(q5 - q16) * w16^2
            - 4 * sin(q5 - q17) * w17^2
            - 3 * sin(q5 - q18) * w18^2
            - 2 * sin(q5 - q19) * w19^2
            - 1 * sin(q5 - q20) * w20^2
            - g / l * 16 * sin(q5);
        link6: 15 * cos(q6 - q1) * der(w1)
            + 15 * cos(q6 - q2) * der(w2)
            + 15 * cos(q6 - q3) * der(w3)
            + 15 * cos(q6 - q4) * der(w4)
            + 15 * cos(q6 - q5) * der(w5)
            + 15 * der(w6)
            + 14 * cos(q6 - q7) * der(w7)
            + 13 * cos(q6 - q8) * der(w8)
            + 12 * cos(q6 - q9) * der(w9)
            + 11 * cos(q6 - q10) * der(w10)
            + 10 * cos(q6 - q11) * der(w11)
            + 9 * cos(q6 - q12) * der(w12)
            + 8 * cos(q6 - q13) * der(w13)
            + 7 * cos(q6 - q14) * der(w14)
            + 6 * cos(q6 - q15) * der(w15)
            + 5 * cos(q6 - q16) * der(w16)
            + 4 * cos(q6 - q17) * der(w17)
            + 3 * cos(q6 - q18) * der(w18)
            + 2 * cos(q6 - q19) * der(w19)
            + 1 * cos(q6 - q20) * der(w20)
            = -15 * sin(q6 - q1) * w1^2
            - 15 * sin(q6 - q2) * w2^2
            - 15 * sin(q6 - q3) * w3^2
            - 15 * sin(q6 - q4) * w4^2
            - 15 * sin(q6 - q5) * w5^2
            - 14 * sin(q6 - q7) * w7^2
            - 13 * sin(q6 - q8) * w8^2
            - 12 * sin(q6 - q9) * w9^2
            - 11 * sin(q6 - q10) * w10^2
            - 10 * sin(q6 - q11) * w11^2
            - 9 * sin(q6 - q12) * w12^2
            - 8 * sin(q6 - q13) * w13^2
            - 7 * sin(q6 - q14) * w14^2
            - 6 * sin(q6 - q15) * w15^2
            - 5 * sin(q6 - q16) * w16^2
            - 4 * sin(q6 - q17) * w17^2
            - 3 * sin(q6 - q18) * w18^2
            - 2 * sin(q6 - q19) * w19^2
            - 1 * sin(q6 - q20) * w20^2
            - g / l * 15 * sin(q6);
        link7: 14 * cos(q7 - q1) * der(w1)
            + 14 * cos(q7 - q2) * der(w2)
            + 14 * cos(q7 - q3) * der(w3)
            + 14 * cos(q7 - q4) * der(w4)
            + 14 * cos(q7 - q5) * der(w5)
            + 14 * cos(q7 - q6) * der(w6)
            + 14 * der(w7)
            + 13 * cos(q7 - q8) * der(w8)
            + 12 * cos(q7 - q9) * der(w9)
            + 11 * cos(q7 - q10) * der(w10)
            + 10 * cos(q7 - q11) * der(w11)
            + 9 * cos(q7 - q12) * der(w12)
            + 8 * cos(q7 - q13) * der(w13)
            + 7 * cos(q7 - q14) * der(w14)
            + 6 * cos(q7 - q15) * der(w15)
            + 5 * cos(q7 - q16) * der(w16)
            + 4 * cos(q7 - q17) * der(w17)
            + 3 * cos(q7 - q18) * der(w18)
            + 2 * cos(q7 - q19) * der(w19)
            + 1 * cos(q7 - q20) * der(w20)
            = -14 * sin(q7 - q1) * w1^2
            - 14 * sin(q7 - q2) * w2^2
            - 14 * sin(q7 - q3) * w3^2
            - 14 * sin(q7 - q4) * w4^2
            - 14 * sin(q7 - q5) * w5^2
            - 14 * sin(q7 - q6) * w6^2
            - 13 * sin(q7 - q8) * w8^2
            - 12 * sin(q7 - q9) * w9^2
            - 11 * sin(q7 - q10) * w10^2
            - 10 * sin(q7 - q11) * w11^2
            - 9 * sin(q7 - q12) * w12^2
            - 8 * sin(q7 - q13) * w13^2
            - 7 * sin(q7 - q14) * w14^2
            - 6 * sin(q7 - q15) * w15^2
            - 5 * sin(q7 - q16) * w16^2
            - 4 * sin(q7 - q17) * w17^2
            - 3 * sin(q7 - q18) * w18^2
            - 2 * sin(q7 - q19) * w19^2
            - 1 * sin(q7 - q20) * w20^2
            - g / l * 14 * sin(q7);
        link8: 13 * cos(q8 - q1) * der(w1)
            + 13 * cos(q8 - q2) * der(w2)
            + 13 * cos(q8 - q3) * der(w3)
            + 13 * cos(q8 - q4) * der(w4)
            + 13 * cos(q8 - q5) * der(w5)
            + 13 * cos(q8 - q6) * der(w6)
            + 13 * cos(q8 - q7) * der(w7)
            + 13 * der(w8)
            + 12 * cos(q8 - q9) * der(w9)
            + 11 * cos(q8 - q10) * der(w10)
            + 10 * cos(q8 - q11) * der(w11)
            + 9 * cos(q8 - q12) * der(w12)
            + 8 * cos(q8 - q13) * der(w13)
            + 7 * cos(q8 - q14) * der(w14)
            + 6 * cos(q8 - q15) * der(w15)
            + 5 * cos(q8 - q16) * der(w16)
            + 4 * cos(q8 - q17) * der(w17)
            + 3 * cos(q8 - q18) * der(w18)
            + 2 * cos(q8 - q19) * der(w19)
            + 1 * cos(q8 - q20) * der(w20)
            = -13 * sin(q8 - q1) * w1^2
            - 13 * sin(q8 - q2) * w2^2
            - 13 * sin(q8 - q3) * w3^2
            - 13 * sin(q8 - q4) * w4^2
            - 13 * sin(q8 - q5) * w5^2
            - 13 * sin(q8 - q6) * w6^2
            - 13 * sin(q8 - q7) * w7^2
            - 12 * sin(q8 - q9) * w9^2
            - 11 * sin(q8 - q10) * w10^2
            - 10 * sin(q8 - q11) * w11^2
            - 9 * sin(q8 - q12) * w12^2
            - 8 * sin(q8 - q13) * w13^2
            - 7 * sin(q8 - q14) * w14^2
            - 6 * sin(q8 - q15) * w15^2
            - 5 * sin(q8 - q16) * w16^2
            - 4 * sin(q8 - q17) * w17^2
            - 3 * sin(q8 - q18) * w18^2
            - 2 * sin(q8 - q19) * w19^2
            - 1 * sin(q8 - q20) * w20^2
            - g / l * 13 * sin(q8);
        link9: 12 * cos(q9 - q1) * der(w1)
            + 12 * cos(q9 - q2) * der(w2)
            + 12 * cos(q9 - q3) * der(w3)
            + 12 * cos(q9 - q4) * der(w4)
            + 12 * cos(q9 - q5) * der(w5)
            + 12 * cos(q9 - q6) * der(w6)
            + 12 * cos(q9 - q7) * der(w7)
            + 12 * cos(q9 - q8) * der(w8)
            + 12 * der(w9)
            + 11 * cos(q9 - q10) * der(w10)
            + 10 * cos(q9 - q11) * der(w11)
            + 9 * cos(q9 - q12) * der(w12)
            + 8 * cos(q9 - q13) * der(w13)
            + 7 * cos(q9 - q14) * der(w14)
            + 6 * cos(q9 - q15) * der(w15)
            + 5 * cos(q9 - q16) * der(w16)
            + 4 * cos(q9 - q17) * der(w17)
            + 3 * cos(q9 - q18) * der(w18)
            + 2 * cos(q9 - q19) * der(w19)
            + 1 * cos(q9 - q20) * der(w20)
            = -12 * sin(q9 - q1) * w1^2
            - 12 * sin(q9 - q2) * w2^2
            - 12 * sin(q9 - q3) * w3^2
            - 12 * sin(q9 - q4) * w4^2
            - 12 * sin(q9 - q5) * w5^2
            - 12 * sin(q9 - q6) * w6^2
            - 12 * sin(q9 - q7) * w7^2
            - 12 * sin(q9 - q8) * w8^2
            - 11 * sin(q9 - q10) * w10^2
            - 10 * sin(q9 - q11) * w11^2
            - 9 * sin(q9 - q12) * w12^2
            - 8 * sin(q9 - q13) * w13^2
            - 7 * sin(q9 - q14) * w14^2
            - 6 * sin(q9 - q15) * w15^2
            - 5 * sin(q9 - q16) * w16^2
            - 4 * sin(q9 - q17) * w17^2
            - 3 * sin(q9 - q18) * w18^2
            - 2 * sin(q9 - q19) * w19^2
            - 1 * sin(q9 - q20) * w20^2
            - g / l * 12 * sin(q9);
        link10: 11 * cos(q10 - q1) * der(w1)
            + 11 * cos(q10 - q2) * der(w2)
            + 11 * cos(q10 - q3) * der(w3)
            + 11 * cos(q10 - q4) * der(w4)
            + 11 * cos(q10 - q5) * der(w5)
            + 11 * cos(q10 - q6) * der(w6)
            + 11 * cos(q10 - q7) * der(w7)
            + 11 * cos(q10 - q8) * der(w8)
            + 11 * cos(q10 - q9) * der(w9)
            + 11 * der(w10)
            + 10 * cos(q10 - q11) * der(w11)
            + 9 * cos(q10 - q12) * der(w12)
            + 8 * cos(q10 - q13) * der(w13)
            + 7 * cos(q10 - q14) * der(w14)
            + 6 * cos(q10 - q15) * der(w15)
            + 5 * cos(q10 - q16) * der(w16)
            + 4 * cos(q10 - q17) * der(w17)
            + 3 * cos(q10 - q18) * der(w18)
            + 2 * cos(q10 - q19) * der(w19)
            + 1 * cos(q10 - q20) * der(w20)
            = -11 * sin(q10 - q1) * w1^2
            - 11 * sin(q10 - q2) * w2^2
            - 11 * sin(q10 - q3) * w3^2
            - 11 * sin(q10 - q4) * w4^2
            - 11 * sin(q10 - q5) * w5^2
            - 11 * sin(q10 - q6) * w6^2
            - 11 * sin(q10 - q7) * w7^2
            - 11 * sin(q10 - q8) * w8^2
            - 11 * sin(q10 - q9) * w9^2
            - 10 * sin(q10 - q11) * w11^2
            - 9 * sin(q10 - q12) * w12^2
            - 8 * sin(q10 - q13) * w13^2
            - 7 * sin(q10 - q14) * w14^2
            - 6 * sin(q10 - q15) * w15^2
            - 5 * sin(q10 - q16) * w16^2
            - 4 * sin(q10 - q17) * w17^2
            - 3 * sin(q10 - q18) * w18^2
            - 2 * sin(q10 - q19) * w19^2
            - 1 * sin(q10 - q20) * w20^2
            - g / l * 11 * sin(q10);
        link11: 10 * cos(q11 - q1) * der(w1)
            + 10 * cos(q11 - q2) * der(w2)
            + 10 * cos(q11 - q3) * der(w3)
            + 10 * cos(q11 - q4) * der(w4)
            + 10 * cos(q11 - q5) * der(w5)
            + 10 * cos(q11 - q6) * der(w6)
            + 10 * cos(q11 - q7) * der(w7)
            + 10 * cos(q11 - q8) * der(w8)
            + 10 * cos(q11 - q9) * der(w9)
            + 10 * cos(q11 - q10) * der(w10)
            + 10 * der(w11)
            + 9 * cos(q11 - q12) * der(w12)
            + 8 * cos(q11 - q13) * der(w13)
            + 7 * cos(q11 - q14) * der(w14)
            + 6 * cos(q11 - q15) * der(w15)
            + 5 * cos(q11 - q16) * der(w16)
            + 4 * cos(q11 - q17) * der(w17)
            + 3 * cos(q11 - q18) * der(w18)
            + 2 * cos(q11 - q19) * der(w19)
            + 1 * cos(q11 - q20) * der(w20)
            = -10 * sin(q11 - q1) * w1^2
            - 10 * sin(q11 - q2) * w2^2
            - 10 * sin(q11 - q3) * w3^2
            - 10 * sin(q11 - q4) * w4^2
            - 10 * sin(q11 - q5) * w5^2
            - 10 * sin(q11 - q6) * w6^2
            - 10 * sin(q11 - q7) * w7^2
            - 10 * sin(q11 - q8) * w8^2
            - 10 * sin(q11 - q9) * w9^2
            - 10 * sin(q11 - q10) * w10^2
            - 9 * sin(q11 - q12) * w12^2
            - 8 * sin(q11 - q13) * w13^2
            - 7 * sin(q11 - q14) * w14^2
            - 6 * sin(q11 - q15) * w15^2
            - 5 * sin(q11 - q16) * w16^2
            - 4 * sin(q11 - q17) * w17^2
            - 3 * sin(q11 - q18) * w18^2
            - 2 * sin(q11 - q19) * w19^2
            - 1 * sin(q11 - q20) * w20^2
            - g / l * 10 * sin(q11);
        link12: 9 * cos(q12 - q1) * der(w1)
            + 9 * cos(q12 - q2) * der(w2)
            + 9 * cos(q12 - q3) * der(w3)
            + 9 * cos(q12 - q4) * der(w4)
            + 9 * cos(q12 - q5) * der(w5)
            + 9 * cos(q12 - q6) * der(w6)
            + 9 * cos(q12 - q7) * der(w7)
            + 9 * cos(q12 - q8) * der(w8)
            + 9 * cos(q12 - q9) * der(w9)
            + 9 * cos(q12 - q10) * der(w10)
            + 9 * cos(q12 - q11) * der(w11)
            + 9 * der(w12)
            + 8 * cos(q12 - q13) * der(w13)
            + 7 * cos(q12 - q14) * der(w14)
            + 6 * cos(q12 - q15) * der(w15)
            + 5 * cos(q12 - q16) * der(w16)
            + 4 * cos(q12 - q17) * der(w17)
            + 3 * cos(q12 - q18) * der(w18)
            + 2 * cos(q12 - q19) * der(w19)
            + 1 * cos(q12 - q20) * der(w20)
            = -9 * sin(q12 - q1) * w1^2
            - 9 * sin(q12 - q2) * w2^2
            - 9 * sin(q12 - q3) * w3^2
            - 9 * sin(q12 - q4) * w4^2
            - 9 * sin(q12 - q5) * w5^2
            - 9 * sin(q12 - q6) * w6^2
            - 9 * sin(q12 - q7) * w7^2
            - 9 * sin(q12 - q8) * w8^2
            - 9 * sin(q12 - q9) * w9^2
            - 9 * sin(q12 - q10) * w10^2
            - 9 * sin(q12 - q11) * w11^2
            - 8 * sin(q12 - q13) * w13^2
            - 7 * sin(q12 - q14) * w14^2
            - 6 * sin(q12 - q15) * w15^2
            - 5 * sin(q12 - q16) * w16^2
            - 4 * sin(q12 - q17) * w17^2
            - 3 * sin(q12 - q18) * w18^2
            - 2 * sin(q12 - q19) * w19^2
            - 1 * sin(q12 - q20) * w20^2
            - g / l * 9 * sin(q12);
        link13: 8 * cos(q13 - q1) * der(w1)
            + 8 * cos(q13 - q2) * der(w2)
            + 8 * cos(q13 - q3) * der(w3)
            + 8 * cos(q13 - q4) * der(w4)
            + 8 * cos(q13 - q5) * der(w5)
            + 8 * cos(q13 - q6) * der(w6)
            + 8 * cos(q13 - q7) * der(w7)
            + 8 * cos(q13 - q8) * der(w8)
            + 8 * cos(q13 - q9) * der(w9)
            + 8 * cos(q13 - q10) * der(w10)
            + 8 * cos(q13 - q11) * der(w11)
            + 8 * cos(q13 - q12) * der(w12)
            + 8 * der(w13)
            + 7 * cos(q13 - q14) * der(w14)
            + 6 * cos(q13 - q15) * der(w15)
            + 5 * cos(q13 - q16) * der(w16)
            + 4 * cos(q13 - q17) * der(w17)
            + 3 * cos(q13 - q18) * der(w18)
            + 2 * cos(q13 - q19) * der(w19)
            + 1 * cos(q13 - q20) * der(w20)
            = -8 * sin(q13 - q1) * w1^2
            - 8 * sin(q13 - q2) * w2^2
            - 8 * sin(q13 - q3) * w3^2
            - 8 * sin(q13 - q4) * w4^2
            - 8 * sin(q13 - q5) * w5^2
            - 8 * sin(q13 - q6) * w6^2
            - 8 * sin(q13 - q7) * w7^2
            - 8 * sin(q13 - q8) * w8^2
            - 8 * sin(q13 - q9) * w9^2
            - 8 * sin(q13 - q10) * w10^2
            - 8 * sin(q13 - q11) * w11^2
            - 8 * sin(q13 - q12) * w12^2
            - 7 * sin(q13 - q14) * w14^2
            - 6 * sin(q13 - q15) * w15^2
            - 5 * sin(q13 - q16) * w16^2
            - 4 * sin(q13 - q17) * w17^2
            - 3 * sin(q13 - q18) * w18^2
            - 2 * sin(q13 - q19) * w19^2
            - 1 * sin(q13 - q20) * w20^2
            - g / l * 8 * sin(q13);
        link14: 7 * cos(q14 - q1) * der(w1)
            + 7 * cos(q14 - q2) * der(w2)
            + 7 * cos(q14 - q3) * der(w3)
            + 7 * cos(q14 - q4) * der(w4)
            + 7 * cos(q14 - q5) * der(w5)
            + 7 * cos(q14 - q6) * der(w6)
            + 7 * cos(q14 - q7) * der(w7)
            + 7 * cos(q14 - q8) * der(w8)
            + 7 * cos(q14 - q9) * der(w9)
            + 7 * cos(q14 - q10) * der(w10)
            + 7 * cos(q14 - q11) * der(w11)
            + 7 * cos(q14 - q12) * der(w12)
            + 7 * cos(q14 - q13) * der(w13)
            + 7 * der(w14)
            + 6 * cos(q14 - q15) * der(w15)
            + 5 * cos(q14 - q16) * der(w16)
            + 4 * cos(q14 - q17) * der(w17)
            + 3 * cos(q14 - q18) * der(w18)
            + 2 * cos(q14 - q19) * der(w19)
            + 1 * cos(q14 - q20) * der(w20)
            = -7 * sin(q14 - q1) * w1^2
            - 7 * sin(q14 - q2) * w2^2
            - 7 * sin(q14 - q3) * w3^2
            - 7 * sin(q14 - q4) * w4^2
            - 7 * sin(q14 - q5) * w5^2
            - 7 * sin(q14 - q6) * w6^2
            - 7 * sin(q14 - q7) * w7^2
            - 7 * sin(q14 - q8) * w8^2
            - 7 * sin(q14 - q9) * w9^2
            - 7 * sin(q14 - q10) * w10^2
            - 7 * sin(q14 - q11) * w11^2
            - 7 * sin(q14 - q12) * w12^2
            - 7 * sin(q14 - q13) * w13^2
            - 6 * sin(q14 - q15) * w15^2
            - 5 * sin(q14 - q16) * w16^2
            - 4 * sin(q14 - q17) * w17^2
            - 3 * sin(q14 - q18) * w18^2
            - 2 * sin(q14 - q19) * w19^2
            - 1 * sin(q14 - q20) * w20^2
            - g / l * 7 * sin(q14);
        link15: 6 * cos(q15 - q1) * der(w1)
            + 6 * cos(q15 - q2) * der(w2)
            + 6 * cos(q15 - q3) * der(w3)
            + 6 * cos(q15 - q4) * der(w4)
            + 6 * cos(q15 - q5) * der(w5)
            + 6 * cos(q15 - q6) * der(w6)
            + 6 * cos(q15 - q7) * der(w7)
            + 6 * cos(q15 - q8) * der(w8)
            + 6 * cos(q15 - q9) * der(w9)
            + 6 * cos(q15 - q10) * der(w10)
            + 6 * cos(q15 - q11) * der(w11)
            + 6 * cos(q15 - q12) * der(w12)
            + 6 * cos(q15 - q13) * der(w13)
            + 6 * cos(q15 - q14) * der(w14)
            + 6 * der(w15)
            + 5 * cos(q15 - q16) * der(w16)
            + 4 * cos(q15 - q17) * der(w17)
            + 3 * cos(q15 - q18) * der(w18)
            + 2 * cos(q15 - q19) * der(w19)
            + 1 * cos(q15 - q20) * der(w20)
            = -6 * sin(q15 - q1) * w1^2
            - 6 * sin(q15 - q2) * w2^2
            - 6 * sin(q15 - q3) * w3^2
            - 6 * sin(q15 - q4) * w4^2
            - 6 * sin(q15 - q5) * w5^2
            - 6 * sin(q15 - q6) * w6^2
            - 6 * sin(q15 - q7) * w7^2
            - 6 * sin(q15 - q8) * w8^2
            - 6 * sin(q15 - q9) * w9^2
            - 6 * sin(q15 - q10) * w10^2
            - 6 * sin(q15 - q11) * w11^2
            - 6 * sin(q15 - q12) * w12^2
            - 6 * sin(q15 - q13) * w13^2
            - 6 * sin(q15 - q14) * w14^2
            - 5 * sin(q15 - q16) * w16^2
            - 4 * sin(q15 - q17) * w17^2
            - 3 * sin(q15 - q18) * w18^2
            - 2 * sin(q15 - q19) * w19^2
            - 1 * sin(q15 - q20) * w20^2
            - g / l * 6 * sin(q15);
        link16: 5 * cos(q16 - q1) * der(w1)
            + 5 * cos(q16 - q2) * der(w2)
            + 5 * cos(q16 - q3) * der(w3)
            + 5 * cos(q16 - q4) * der(w4)
            + 5 * cos(q16 - q5) * der(w5)
            + 5 * cos(q16 - q6) * der(w6)
            + 5 * cos(q16 - q7) * der(w7)
            + 5 * cos(q16 - q8) * der(w8)
            + 5 * cos(q16 - q9) * der(w9)
            + 5 * cos(q16 - q10) * der(w10)
            + 5 * cos(q16 - q11) * der(w11)
            + 5 * cos(q16 - q12) * der(w12)
            + 5 * cos(q16 - q13) * der(w13)
            + 5 * cos(q16 - q14) * der(w14)
            + 5 * cos(q16 - q15) * der(w15)
            + 5 * der(w16)
            + 4 * cos(q16 - q17) * der(w17)
            + 3 * cos(q16 - q18) * der(w18)
            + 2 * cos(q16 - q19) * der(w19)
            + 1 * cos(q16 - q20) * der(w20)
            = -5 * sin(q16 - q1) * w1^2
            - 5 * sin(q16 - q2) * w2^2
            - 5 * sin(q16 - q3) * w3^2
            - 5 * sin(q16 - q4) * w4^2
            - 5 * sin(q16 - q5) * w5^2
            - 5 * sin(q16 - q6) * w6^2
            - 5 * sin(q16 - q7) * w7^2
            - 5 * sin(q16 - q8) * w8^2
            - 5 * sin(q16 - q9) * w9^2
            - 5 * sin(q16 - q10) * w10^2
            - 5 * sin(q16 - q11) * w11^2
            - 5 * sin(q16 - q12) * w12^2
            - 5 * sin(q16 - q13) * w13^2
            - 5 * sin(q16 - q14) * w14^2
            - 5 * sin(q16 - q15) * w15^2
            - 4 * sin(q16 - q17) * w17^2
            - 3 * sin(q16 - q18) * w18^2
            - 2 * sin(q16 - q19) * w19^2
            - 1 * sin(q16 - q20) * w20^2
            - g / l * 5 * sin(q16);
        link17: 4 * cos(q17 - q1) * der(w1)
            + 4 * cos(q17 - q2) * der(w2)
            + 4 * cos(q17 - q3) * der(w3)
            + 4 * cos(q17 - q4) * der(w4)
            + 4 * cos(q17 - q5) * der(w5)
            + 4 * cos(q17 - q6) * der(w6)
            + 4 * cos(q17 - q7) * der(w7)
            + 4 * cos(q17 - q8) * der(w8)
            + 4 * cos(q17 - q9) * der(w9)
            + 4 * cos(q17 - q10) * der(w10)
            + 4 * cos(q17 - q11) * der(w11)
            + 4 * cos(q17 - q12) * der(w12)
            + 4 * cos(q17 - q13) * der(w13)
            + 4 * cos(q17 - q14) * der(w14)
            + 4 * cos(q17 - q15) * der(w15)
            + 4 * cos(q17 - q16) * der(w16)
            + 4 * der(w17)
            + 3 * cos(q17 - q18) * der(w18)
            + 2 * cos(q17 - q19) * der(w19)
            + 1 * cos(q17 - q20) * der(w20)
            = -4 * sin(q17 - q1) * w1^2
            - 4 * sin(q17 - q2) * w2^2
            - 4 * sin(q17 - q3) * w3^2
            - 4 * sin(q17 - q4) * w4^2
            - 4 * sin(q17 - q5) * w5^2
            - 4 * sin(q17 - q6) * w6^2
            - 4 * sin(q17 - q7) * w7^2
            - 4 * sin(q17 - q8) * w8^2
            - 4 * sin(q17 - q9) * w9^2
            - 4 * sin(q17 - q10) * w10^2
            - 4 * sin(q17 - q11) * w11^2
            - 4 * sin(q17 - q12) * w12^2
            - 4 * sin(q17 - q13) * w13^2
            - 4 * sin(q17 - q14) * w14^2
            - 4 * sin(q17 - q15) * w15^2
            - 4 * sin(q17 - q16) * w16^2
            - 3 * sin(q17 - q18) * w18^2
            - 2 * sin(q17 - q19) * w19^2
            - 1 * sin(q17 - q20) * w20^2
            - g / l * 4 * sin(q17);
        link18: 3 * cos(q18 - q1) * der(w1)
            + 3 * cos(q18 - q2) * der(w2)
            + 3 * cos(q18 - q3) * der(w3)
            + 3 * cos(q18 - q4) * der(w4)
            + 3 * cos(q18 - q5) * der(w5)
            + 3 * cos(q18 - q6) * der(w6)
            + 3 * cos(q18 - q7) * der(w7)
            + 3 * cos(q18 - q8) * der(w8)
            + 3 * cos(q18 - q9) * der(w9)
            + 3 * cos(q18 - q10) * der(w10)
            + 3 * cos(q18 - q11) * der(w11)
            + 3 * cos(q18 - q12) * der(w12)
            + 3 * cos(q18 - q13) * der(w13)
            + 3 * cos(q18 - q14) * der(w14)
            + 3 * cos(q18 - q15) * der(w15)
            + 3 * cos(q18 - q16) * der(w16)
            + 3 * cos(q18 - q17) * der(w17)
            + 3 * der(w18)
            + 2 * cos(q18 - q19) * der(w19)
            + 1 * cos(q18 - q20) * der(w20)
            = -3 * sin(q18 - q1) * w1^2
            - 3 * sin(q18 - q2) * w2^2
            - 3 * sin(q18 - q3) * w3^2
            - 3 * sin(q18 - q4) * w4^2
            - 3 * sin(q18 - q5) * w5^2
            - 3 * sin(q18 - q6) * w6^2
            - 3 * sin(q18 - q7) * w7^2
            - 3 * sin(q18 - q8) * w8^2
            - 3 * sin(q18 - q9) * w9^2
            - 3 * sin(q18 - q10) * w10^2
            - 3 * sin(q18 - q11) * w11^2
            - 3 * sin(q18 - q12) * w12^2
            - 3 * sin(q18 - q13) * w13^2
            - 3 * sin(q18 - q14) * w14^2
            - 3 * sin(q18 - q15) * w15^2
            - 3 * sin(q18 - q16) * w16^2
            - 3 * sin(q18 - q17) * w17^2
            - 2 * sin(q18 - q19) * w19^2
            - 1 * sin(q18 - q20) * w20^2
            - g / l * 3 * sin(q18);
        link19: 2 * cos(q19 - q1) * der(w1)
            + 2 * cos(q19 - q2) * der(w2)
            + 2 * cos(q19 - q3) * der(w3)
            + 2 * cos(q19 - q4) * der(w4)
            + 2 * cos(q19 - q5) * der(w5)
            + 2 * cos(q19 - q6) * der(w6)
            + 2 * cos(q19 - q7) * der(w7)
            + 2 * cos(q19 - q8) * der(w8)
            + 2 * cos(q19 - q9) * der(w9)
            + 2 * cos(q19 - q10) * der(w10)
            + 2 * cos(q19 - q11) * der(w11)
            + 2 * cos(q19 - q12) * der(w12)
            + 2 * cos(q19 - q13) * der(w13)
            + 2 * cos(q19 - q14) * der(w14)
            + 2 * cos(q19 - q15) * der(w15)
            + 2 * cos(q19 - q16) * der(w16)
            + 2 * cos(q19 - q17) * der(w17)
            + 2 * cos(q19 - q18) * der(w18)
            + 2 * der(w19)
            + 1 * cos(q19 - q20) * der(w20)
            = -2 * sin(q19 - q1) * w1^2
            - 2 * sin(q19 - q2) * w2^2
            - 2 * sin(q19 - q3) * w3^2
            - 2 * sin(q19 - q4) * w4^2
            - 2 * sin(q19 - q5) * w5^2
            - 2 * sin(q19 - q6) * w6^2
            - 2 * sin(q19 - q7) * w7^2
            - 2 * sin(q19 - q8) * w8^2
            - 2 * sin(q19 - q9) * w9^2
            - 2 * sin(q19 - q10) * w10^2
            - 2 * sin(q19 - q11) * w11^2
            - 2 * sin(q19 - q12) * w12^2
            - 2 * sin(q19 - q13) * w13^2
            - 2 * sin(q19 - q14) * w14^2
            - 2 * sin(q19 - q15) * w15^2
            - 2 * sin(q19 - q16) * w16^2
            - 2 * sin(q19 - q17) * w17^2
            - 2 * sin(q19 - q18) * w18^2
            - 1 * sin(q19 - q20) * w20^2
            - g / l * 2 * sin(q19);
        link20: 1 * cos(q20 - q1) * der(w1)
            + 1 * cos(q20 - q2) * der(w2)
            + 1 * cos(q20 - q3) * der(w3)
            + 1 * cos(q20 - q4) * der(w4)
            + 1 * cos(q20 - q5) * der(w5)
            + 1 * cos(q20 - q6) * der(w6)
            + 1 * cos(q20 - q7) * der(w7)
            + 1 * cos(q20 - q8) * der(w8)
            + 1 * cos(q20 - q9) * der(w9)
            + 1 * cos(q20 - q10) * der(w10)
            + 1 * cos(q20 - q11) * der(w11)
            + 1 * cos(q20 - q12) * der(w12)
            + 1 * cos(q20 - q13) * der(w13)
            + 1 * cos(q20 - q14) * der(w14)
            + 1 * cos(q20 - q15) * der(w15)
            + 1 * cos(q20 - q16) * der(w16)
            + 1 * cos(q20 - q17) * der(w17)
            + 1 * cos(q20 - q18) * der(w18)
            + 1 * cos(q20 - q19) * der(w19)
            + 1 * der(w20)
            = -1 * sin(q20 - q1) * w1^2
            - 1 * sin(q20 - q2) * w2^2
            - 1 * sin(q20 - q3) * w3^2
            - 1 * sin(q20 - q4) * w4^2
            - 1 * sin(q20 - q5) * w5^2
            - 1 * sin(q20 - q6) * w6^2
            - 1 * sin(q20 - q7) * w7^2
            - 1 * sin(q20 - q8) * w8^2
            - 1 * sin(q20 - q9) * w9^2
            - 1 * sin(q20 - q10) * w10^2
            - 1 * sin(q20 - q11) * w11^2
            - 1 * sin(q20 - q12) * w12^2
            - 1 * sin(q20 - q13) * w13^2
            - 1 * sin(q20 - q14) * w14^2
            - 1 * sin(q20 - q15) * w15^2
            - 1 * sin(q20 - q16) * w16^2
            - 1 * sin(q20 - q17) * w17^2
            - 1 * sin(q20 - q18) * w18^2
            - 1 * sin(q20 - q19) * w19^2
            - g / l * 1 * sin(q20);
    }
    outputs {
        energy = m * l^2 * (20 / 2 * w1^2
            + 19 * cos(q1 - q2) * w1 * w2
            + 18 * cos(q1 - q3) * w1 * w3
            + 17 * cos(q1 - q4) * w1 * w4
            + 16 * cos(q1 - q5) * w1 * w5
            + 15 * cos(q1 - q6) * w1 * w6
            + 14 * cos(q1 - q7) * w1 * w7
            + 13 * cos(q1 - q8) * w1 * w8
            + 12 * cos(q1 - q9) * w1 * w9
            + 11 * cos(q1 - q10) * w1 * w10
            + 10 * cos(q1 - q11) * w1 * w11
            + 9 * cos(q1 - q12) * w1 * w12
            + 8 * cos(q1 - q13) * w1 * w13
            + 7 * cos(q1 - q14) * w1 * w14
            + 6 * cos(q1 - q15) * w1 * w15
            + 5 * cos(q1 - q16) * w1 * w16
            + 4 * cos(q1 - q17) * w1 * w17
            + 3 * cos(q1 - q18) * w1 * w18
            + 2 * cos(q1 - q19) * w1 * w19
            + 1 * cos(q1 - q20) * w1 * w20
            + 19 / 2 * w2^2
            + 18 * cos(q2 - q3) * w2 * w3
            + 17 * cos(q2 - q4) * w2 * w4
            + 16 * cos(q2 - q5) * w2 * w5
            + 15 * cos(q2 - q6) * w2 * w6
            + 14 * cos(q2 - q7) * w2 * w7
            + 13 * cos(q2 - q8) * w2 * w8
            + 12 * cos(q2 - q9) * w2 * w9
            + 11 * cos(q2 - q10) * w2 * w10
            + 10 * cos(q2 - q11) * w2 * w11
            + 9 * cos(q2 - q12) * w2 * w12
            + 8 * cos(q2 - q13) * w2 * w13
            + 7 * cos(q2 - q14) * w2 * w14
            + 6 * cos(q2 - q15) * w2 * w15
            + 5 * cos(q2 - q16) * w2 * w16
            + 4 * cos(q2 - q17) * w2 * w17
            + 3 * cos(q2 - q18) * w2 * w18
            + 2 * cos(q2 - q19) * w2 * w19
            + 1 * cos(q2 - q20) * w2 * w20
            + 18 / 2 * w3^2
            + 17 * cos(q3 - q4) * w3 * w4
            + 16 * cos(q3 - q5) * w3 * w5
            + 15 * cos(q3 - q6) * w3 * w6
            + 14 * cos(q3 - q7) * w3 * w7
            + 13 * cos(q3 - q8) * w3 * w8
            + 12 * cos(q3 - q9) * w3 * w9
            + 11 * cos(q3 - q10) * w3 * w10
            + 10 * cos(q3 - q11) * w3 * w11
            + 9 * cos(q3 - q12) * w3 * w12
            + 8 * cos(q3 - q13) * w3 * w13
            + 7 * cos(q3 - q14) * w3 * w14
            + 6 * cos(q3 - q15) * w3 * w15
            + 5 * cos(q3 - q16) * w3 * w16
            + 4 * cos(q3 - q17) * w3 * w17
            + 3 * cos(q3 - q18) * w3 * w18
            + 2 * cos(q3 - q19) * w3 * w19
            + 1 * cos(q3 - q20) * w3 * w20
            + 17 / 2 * w4^2
            + 16 * cos(q4 - q5) * w4 * w5
            + 15 * cos(q4 - q6) * w4 * w6
            + 14 * cos(q4 - q7) * w4 * w7
            + 13 * cos(q4 - q8) * w4 * w8
            + 12 * cos(q4 - q9) * w4 * w9
            + 11 * cos(q4 - q10) * w4 * w10
            + 10 * cos(q4 - q11) * w4 * w11
            + 9 * cos(q4 - q12) * w4 * w12
            + 8 * cos(q4 - q13) * w4 * w13
            + 7 * cos(q4 - q14) * w4 * w14
            + 6 * cos(q4 - q15) * w4 * w15
            + 5 * cos(q4 - q16) * w4 * w16
            + 4 * cos(q4 - q17) * w4 * w17
            + 3 * cos(q4 - q18) * w4 * w18
            + 2 * cos(q4 - q19) * w4 * w19
            + 1 * cos(q4 - q20) * w4 * w20
            + 16 / 2 * w5^2
            + 15 * cos(q5 - q6) * w5 * w6
            + 14 * cos(q5 - q7) * w5 * w7
            + 13 * cos(q5 - q8) * w5 * w8
            + 12 * cos(q5 - q9) * w5 * w9
            + 11 * cos(q5 - q10) * w5 * w10
            + 10 * cos(q5 - q11) * w5 * w11
            + 9 * cos(q5 - q12) * w5 * w12
            + 8 * cos(q5 - q13) * w5 * w13
            + 7 * cos(q5 - q14) * w5 * w14
            + 6 * cos(q5 - q15) * w5 * w15
            + 5 * cos(q5 - q16) * w5 * w16
            + 4 * cos(q5 - q17) * w5 * w17
            + 3 * cos(q5 - q18) * w5 * w18
            + 2 * cos(q5 - q19) * w5 * w19
            + 1 * cos(q5 - q20) * w5 * w20
            + 15 / 2 * w6^2
            + 14 * cos(q6 - q7) * w6 * w7
            + 13 * cos(q6 - q8) * w6 * w8
            + 12 * cos(q6 - q9) * w6 * w9
            + 11 * cos(q6 - q10) * w6 * w10
            + 10 * cos(q6 - q11) * w6 * w11
            + 9 * cos(q6 - q12) * w6 * w12
            + 8 * cos(q6 - q13) * w6 * w13
            + 7 * cos(q6 - q14) * w6 * w14
            + 6 * cos(q6 - q15) * w6 * w15
            + 5 * cos(q6 - q16) * w6 * w16
            + 4 * cos(q6 - q17) * w6 * w17
            + 3 * cos(q6 - q18) * w6 * w18
            + 2 * cos(q6 - q19) * w6 * w19
            + 1 * cos(q6 - q20) * w6 * w20
            + 14 / 2 * w7^2
            + 13 * cos(q7 - q8) * w7 * w8
            + 12 * cos(q7 - q9) * w7 * w9
            + 11 * cos(q7 - q10) * w7 * w10
            + 10 * cos(q7 - q11) * w7 * w11
            + 9 * cos(q7 - q12) * w7 * w12
            + 8 * cos(q7 - q13) * w7 * w13
            + 7 * cos(q7 - q14) * w7 * w14
            + 6 * cos(q7 - q15) * w7 * w15
            + 5 * cos(q7 - q16) * w7 * w16
            + 4 * cos(q7 - q17) * w7 * w17
            + 3 * cos(q7 - q18) * w7 * w18
            + 2 * cos(q7 - q19) * w7 * w19
            + 1 * cos(q7 - q20) * w7 * w20
            + 13 / 2 * w8^2
            + 12 * cos(q8 - q9) * w8 * w9
            + 11 * cos(q8 - q10) * w8 * w10
            + 10 * cos(q8 - q11) * w8 * w11
            + 9 * cos(q8 - q12) * w8 * w12
            + 8 * cos(q8 - q13) * w8 * w13
            + 7 * cos(q8 - q14) * w8 * w14
            + 6 * cos(q8 - q15) * w8 * w15
            + 5 * cos(q8 - q16) * w8 * w16
            + 4 * cos(q8 - q17) * w8 * w17
            + 3 * cos(q8 - q18) * w8 * w18
            + 2 * cos(q8 - q19) * w8 * w19
            + 1 * cos(q8 - q20) * w8 * w20
            + 12 / 2 * w9^2
            + 11 * cos(q9 - q10) * w9 * w10
            + 10 * cos(q9 - q11) * w9 * w11
            + 9 * cos(q9 - q12) * w9 * w12
            + 8 * cos(q9 - q13) * w9 * w13
            + 7 * cos(q9 - q14) * w9 * w14
            + 6 * cos(q9 - q15) * w9 * w15
            + 5 * cos(q9 - q16) * w9 * w16
            + 4 * cos(q9 - q17) * w9 * w17
            + 3 * cos(q9 - q18) * w9 * w18
            + 2 * cos(q9 - q19) * w9 * w19
            + 1 * cos(q9 - q20) * w9 * w20
            + 11 / 2 * w10^2
            + 10 * cos(q10 - q11) * w10 * w11
            + 9 * cos(q10 - q12) * w10 * w12
            + 8 * cos(q10 - q13) * w10 * w13
            + 7 * cos(q10 - q14) * w10 * w14
            + 6 * cos(q10 - q15) * w10 * w15
            + 5 * cos(q10 - q16) * w10 * w16
            + 4 * cos(q10 - q17) * w10 * w17
            + 3 * cos(q10 - q18) * w10 * w18
            + 2 * cos(q10 - q19) * w10 * w19
            + 1 * cos(q10 - q20) * w10 * w20
            + 10 / 2 * w11^2
            + 9 * cos(q11 - q12) * w11 * w12
            + 8 * cos(q11 - q13) * w11 * w13
            + 7 * cos(q11 - q14) * w11 * w14
            + 6 * cos(q11 - q15) * w11 * w15
            + 5 * cos(q11 - q16) * w11 * w16
            + 4 * cos(q11 - q17) * w11 * w17
            + 3 * cos(q11 - q18) * w11 * w18
            + 2 * cos(q11 - q19) * w11 * w19
            + 1 * cos(q11 - q20) * w11 * w20
            + 9 / 2 * w12^2
            + 8 * cos(q12 - q13) * w12 * w13
            + 7 * cos(q12 - q14) * w12 * w14
            + 6 * cos(q12 - q15) * w12 * w15
            + 5 * cos(q12 - q16) * w12 * w16
            + 4 * cos(q12 - q17) * w12 * w17
            + 3 * cos(q12 - q18) * w12 * w18
            + 2 * cos(q12 - q19) * w12 * w19
            + 1 * cos(q12 - q20) * w12 * w20
            + 8 / 2 * w13^2
            + 7 * cos(q13 - q14) * w13 * w14
            + 6 * cos(q13 - q15) * w13 * w15
            + 5 * cos(q13 - q16) * w13 * w16
            + 4 * cos(q13 - q17) * w13 * w17
            + 3 * cos(q13 - q18) * w13 * w18
            + 2 * cos(q13 - q19) * w13 * w19
            + 1 * cos(q13 - q20) * w13 * w20
            + 7 / 2 * w14^2
            + 6 * cos(q14 - q15) * w14 * w15
            + 5 * cos(q14 - q16) * w14 * w16
            + 4 * cos(q14 - q17) * w14 * w17
            + 3 * cos(q14 - q18) * w14 * w18
            + 2 * cos(q14 - q19) * w14 * w19
            + 1 * cos(q14 - q20) * w14 * w20
            + 6 / 2 * w15^2
            + 5 * cos(q15 - q16) * w15 * w16
            + 4 * cos(q15 - q17) * w15 * w17
            + 3 * cos(q15 - q18) * w15 * w18
            + 2 * cos(q15 - q19) * w15 * w19
            + 1 * cos(q15 - q20) * w15 * w20
            + 5 / 2 * w16^2
            + 4 * cos(q16 - q17) * w16 * w17
            + 3 * cos(q16 - q18) * w16 * w18
            + 2 * cos(q16 - q19) * w16 * w19
            + 1 * cos(q16 - q20) * w16 * w20
            + 4 / 2 * w17^2
            + 3 * cos(q17 - q18) * w17 * w18
            + 2 * cos(q17 - q19) * w17 * w19
            + 1 * cos(q17 - q20) * w17 * w20
            + 3 / 2 * w18^2
            + 2 * cos(q18 - q19) * w18 * w19
            + 1 * cos(q18 - q20) * w18 * w20
            + 2 / 2 * w19^2
            + 1 * cos(q19 - q20) * w19 * w20
            + 1 / 2 * w20^2
            - g / l * (20 * cos(q1)
                + 19 * cos(q2)
                + 18 * cos(q3)
                + 17 * cos(q4)
                + 16 * cos(q5)
                + 15 * cos(q6)
                + 14 * cos(q7)
                + 13 * cos(q8)
                + 12 * cos(q9)
                + 11 * cos(q10)
                + 10 * cos(q11)
                + 9 * cos(q12)
                + 8 * cos(q13)
                + 7 * cos(q14)
                + 6 * cos(q15)
                + 5 * cos(q16)
                + 4 * cos(q17)
                + 3 * cos(q18)
                + 2 * cos(q19)
                + 1 * cos(q20)));
    }
}
