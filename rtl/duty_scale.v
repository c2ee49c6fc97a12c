// duty_scale: DC-link compensation and PWM compare values for the three phases, on ONE
// time-shared registered multiplier (one DSP48A1).
//
//   cmp_x = clamp(((v_x * kdc) + 2^(SH-1)) >>> SH, 0, PWM_HALF_PERIOD),  SH = KDC_FRAC + V_FRAC
//   v_x: phase voltage after min-subtraction (signed V_W, Q.4 PWM ticks at the nominal DC link);
//   kdc = Udc_nom / Udc_measured, unsigned KDC_W bit, 1.0 = 2^KDC_FRAC (0 .. 4.0).
//   The 18x18 signed multiplier takes kdc[KDC_W-2:0]; the top bit of kdc (weight 2^(KDC_W-1))
//   is added as v << (KDC_W-1), so the product is exact for every unsigned kdc.
//   Round half up, then clamp; sat pulses if any phase was clamped (rounded value < 0 or
//   > PWM_HALF_PERIOD).  Bit-exact model: gen/empc/rtlmodel/duty_scale.py.
// Ports:
//   start                1-cycle request; v_a, v_b, v_c, kdc sampled in that cycle; ignored while busy
//   v_a, v_b, v_c        signed V_W-bit, Q.4 PWM ticks (from min_sub)
//   kdc                  unsigned KDC_W-bit DC-link factor
//   busy                 high from the cycle after start up to the cycle before done
//   done                 1-cycle pulse: cmp_*, sat updated (held until the next done)
//   cmp_a, cmp_b, cmp_c  unsigned CW-bit compare values 0..PWM_HALF_PERIOD (for pwm_center)
//   sat                  1-cycle pulse with done if any compare value was clamped
// Parameters: V_W, V_FRAC, KDC_W (18), KDC_FRAC, PWM_HALF_PERIOD (empc_formats.vh),
//   CW = clog2(PWM_HALF_PERIOD + 1) as in pwm_center.
// Latency: done is high 7 cycles after the start cycle (3 issues, product, sum, round/clamp).
// Resources: 1 DSP48A1 (registered A/B inputs, registered product).
// Reset: outputs 0, not busy; a computation in flight is dropped.
`default_nettype none
`include "empc_formats.vh"
module duty_scale #(
    parameter integer V_W             = `EMPC_V_W,
    parameter integer V_FRAC          = `EMPC_V_FRAC,
    parameter integer KDC_W           = `EMPC_KDC_W,
    parameter integer KDC_FRAC        = `EMPC_KDC_FRAC,
    parameter integer PWM_HALF_PERIOD = `EMPC_PWM_HALF_PERIOD,
    parameter integer CW              = $clog2(PWM_HALF_PERIOD + 1)
) (
    input  wire                  clk,
    input  wire                  rst,
    input  wire                  start,
    input  wire signed [V_W-1:0] v_a,
    input  wire signed [V_W-1:0] v_b,
    input  wire signed [V_W-1:0] v_c,
    input  wire [KDC_W-1:0]      kdc,
    output reg                   busy,
    output reg                   done,
    output reg  [CW-1:0]         cmp_a,
    output reg  [CW-1:0]         cmp_b,
    output reg  [CW-1:0]         cmp_c,
    output reg                   sat
);
    localparam integer SH = KDC_FRAC + V_FRAC;        // 20
    localparam integer PW = V_W + KDC_W;              // product width
    localparam integer SW = PW + 1;                   // product + top-bit term
    localparam integer RW = SW - SH;                  // rounded value before clamping
    localparam [31:0]          HP32 = PWM_HALF_PERIOD;
    localparam signed [RW-1:0] HP   = HP32[RW-1:0];

    reg signed [V_W-1:0] r_v0, r_v1, r_v2;
    reg [KDC_W-1:0]      r_k;
    reg                  issuing;
    reg [1:0]            step;

    // multiplier (DSP48A1: A, B, product registers)
    reg signed [V_W-1:0]   mul_a;
    reg signed [KDC_W-1:0] mul_b;
    reg signed [PW-1:0]    mul_p;
    reg signed [V_W-1:0]   a_d;                   // mul_a of the product now in mul_p
    reg signed [RW:0]      s_top;                 // (v * kdc) >>> (SH-1)
    reg c1_v, c2_v, c3_v;
    reg [1:0] c1_i, c2_i, c3_i;
    reg [CW-1:0] t0, t1;
    reg          t_sat;

    wire signed [V_W-1:0] v_sel = (step == 2'd0) ? r_v0 : (step == 2'd1) ? r_v1 : r_v2;

    // exact v * kdc; only the bits from the rounding bit up are kept
    /* verilator lint_off UNUSEDSIGNAL */  // bits below the rounding bit / below the result LSB
    wire signed [SW-1:0] hi   = r_k[KDC_W-1] ? {{(SW-V_W-KDC_W+1){a_d[V_W-1]}}, a_d, {(KDC_W-1){1'b0}}} : {SW{1'b0}};
    wire signed [SW-1:0] prod = {mul_p[PW-1], mul_p} + hi;
    // round half up: ((prod >>> (SH-1)) + 1) >>> 1; the lower SH-1 bits cannot carry
    wire signed [RW:0]   rsum = s_top + {{RW{1'b0}}, 1'b1};
    /* verilator lint_on UNUSEDSIGNAL */
    wire signed [RW-1:0] r    = rsum[RW:1];
    wire                 r_lo = r < 0;
    wire                 r_hi = r > HP;
    wire [CW-1:0]        r_c  = r_lo ? {CW{1'b0}} : r_hi ? HP[CW-1:0] : r[CW-1:0];

    always @(posedge clk) begin
        if (rst) begin
            r_v0 <= {V_W{1'b0}}; r_v1 <= {V_W{1'b0}}; r_v2 <= {V_W{1'b0}}; r_k <= {KDC_W{1'b0}};
            issuing <= 1'b0; step <= 2'd0; busy <= 1'b0;
            mul_a <= {V_W{1'b0}}; mul_b <= {KDC_W{1'b0}}; mul_p <= {PW{1'b0}};
            a_d <= {V_W{1'b0}}; s_top <= {(RW+1){1'b0}};
            c1_v <= 1'b0; c2_v <= 1'b0; c3_v <= 1'b0;
            c1_i <= 2'd0; c2_i <= 2'd0; c3_i <= 2'd0;
            t0 <= {CW{1'b0}}; t1 <= {CW{1'b0}}; t_sat <= 1'b0;
            cmp_a <= {CW{1'b0}}; cmp_b <= {CW{1'b0}}; cmp_c <= {CW{1'b0}};
            done <= 1'b0; sat <= 1'b0;
        end else begin
            done <= 1'b0;
            sat  <= 1'b0;
            if (start && !busy) begin
                r_v0 <= v_a; r_v1 <= v_b; r_v2 <= v_c; r_k <= kdc;
                busy <= 1'b1; issuing <= 1'b1; step <= 2'd0;
            end
            // issue phase `step`
            c1_v <= issuing;
            if (issuing) begin
                mul_a <= v_sel;
                mul_b <= {1'b0, r_k[KDC_W-2:0]};
                c1_i  <= step;
                step  <= step + 2'd1;
                if (step == 2'd2) issuing <= 1'b0;
            end
            // product
            mul_p <= mul_a * mul_b;
            a_d   <= mul_a;
            c2_v  <= c1_v; c2_i <= c1_i;
            // exact v * kdc
            s_top <= prod[SW-1:SH-1];
            c3_v <= c2_v; c3_i <= c2_i;
            // round, clamp, output
            if (c3_v) begin
                if (c3_i == 2'd0) begin
                    t0 <= r_c; t_sat <= r_lo | r_hi;
                end else if (c3_i == 2'd1) begin
                    t1 <= r_c; t_sat <= t_sat | r_lo | r_hi;
                end else begin
                    cmp_a <= t0; cmp_b <= t1; cmp_c <= r_c;
                    sat   <= t_sat | r_lo | r_hi;
                    done  <= 1'b1;
                    busy  <= 1'b0;
                end
            end
        end
    end
endmodule
`default_nettype wire
