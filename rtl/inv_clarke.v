// inv_clarke: inverse Clarke transform of the alpha-beta voltages (paper 000 eq. 35).
//
//   u_a = u_alpha
//   u_b = sat((p - h + 2^(K_SHIFT-1)) >>> K_SHIFT)     p = u_beta * K_SQ3
//   u_c = sat((-p - h + 2^(K_SHIFT-1)) >>> K_SHIFT)    h = u_alpha * 2^(K_SHIFT-1)
//   K_SQ3 = round(2^21 sqrt(3)/2) = 1816187, K_SHIFT = 21; round half up, then saturate.
//   p is computed bit-serially (Horner, MSB first: acc = 2 acc + K[j] u_beta), one adder,
//   no DSP48A1.  Because h - 2^(K_SHIFT-1) = (u_alpha - 1) 2^(K_SHIFT-1) has no low bits, the
//   output stage needs only short adders:
//     qb = p >>> 20,  qc = floor(-p / 2^20) = ~((p - 1) >>> 20) = ~(qb - (p[19:0] == 0)),
//     u_b = (qb + 1 - u_alpha) >>> 1,  u_c = (qc + 1 - u_alpha) >>> 1.
//   Bit-exact model: gen/empc/rtlmodel/inv_clarke.py.  Accuracy: <= 0.51 LSB from float.
// Ports:
//   start              1-cycle request; u_alpha, u_beta sampled in that cycle; ignored while busy
//   u_alpha, u_beta    signed V_W-bit, Q.4 in PWM ticks (from inv_park)
//   busy               high from the cycle after start up to the cycle before done
//   done               1-cycle pulse: u_a, u_b, u_c, sat updated (held until the next done)
//   u_a, u_b, u_c      signed V_W-bit phase voltages, Q.4 in PWM ticks
//   sat                1-cycle pulse with done if u_b or u_c saturated
// Parameters: V_W (default from empc_formats.vh).
// Latency: done is high K_BITS + 3 = 24 cycles after the start cycle.
// Resources: no DSP, no BRAM; one V_W+21 bit adder plus three ~V_W-bit output adders.
// Reset: outputs 0, not busy; a conversion in flight is dropped.
`default_nettype none
`include "empc_formats.vh"
module inv_clarke #(
    parameter integer V_W = `EMPC_V_W
) (
    input  wire                  clk,
    input  wire                  rst,
    input  wire                  start,
    input  wire signed [V_W-1:0] u_alpha,
    input  wire signed [V_W-1:0] u_beta,
    output reg                   busy,
    output reg                   done,
    output reg  signed [V_W-1:0] u_a,
    output reg  signed [V_W-1:0] u_b,
    output reg  signed [V_W-1:0] u_c,
    output reg                   sat
);
    localparam integer K_SHIFT = 21;
    localparam integer K_BITS  = 21;
    localparam [K_BITS-1:0] K_SQ3 = 21'd1816187;      // round(2^21 sqrt(3)/2), checked by the model test
    localparam integer HS  = K_SHIFT - 1;              // 20
    localparam integer AW  = V_W + K_BITS;             // |u_beta * K| < 2^(AW-1)
    localparam integer QW  = AW - HS;                  // p >>> 20
    localparam integer SW  = QW + 1;                   // q + (1 - u_alpha)
    localparam signed [V_W-1:0] YMAX = {1'b0, {(V_W-1){1'b1}}};
    localparam signed [V_W-1:0] YMIN = {1'b1, {(V_W-1){1'b0}}};
    localparam integer CNT_W = $clog2(K_BITS);

    reg signed [V_W-1:0] r_a, r_b;
    reg signed [V_W:0]   w;                            // 1 - u_alpha
    reg signed [AW-1:0]  acc;
    reg [CNT_W-1:0]      cnt;
    reg                  run, fin;

    wire signed [AW-1:0] b_ext  = {{(AW-V_W){r_b[V_W-1]}}, r_b};
    wire signed [AW-1:0] addend = K_SQ3[cnt] ? b_ext : {AW{1'b0}};

    // output stage 1 (fin): qb, qc registered; stage 2 (fin2): + (1 - u_alpha), round, saturate
    wire signed [QW-1:0] qb  = acc[AW-1:HS];
    wire                 z   = (acc[HS-1:0] == {HS{1'b0}});
    wire signed [QW-1:0] qc  = ~(qb - {{(QW-1){1'b0}}, z});
    reg  signed [QW-1:0] r_qb, r_qc;
    reg                  fin2;
    wire signed [SW-1:0] w_e = {{(SW-V_W-1){w[V_W]}}, w};
    /* verilator lint_off UNUSEDSIGNAL */  // bit 0 is below the result LSB
    wire signed [SW-1:0] sb  = {r_qb[QW-1], r_qb} + w_e;
    wire signed [SW-1:0] sc  = {r_qc[QW-1], r_qc} + w_e;
    /* verilator lint_on UNUSEDSIGNAL */
    wire signed [SW-2:0] rb  = sb[SW-1:1];
    wire signed [SW-2:0] rc  = sc[SW-1:1];
    // out of range iff the bits from V_W-1 up are not all equal (no comparator needed)
    wire b_ovf = ~(&rb[SW-2:V_W-1] | ~|rb[SW-2:V_W-1]);
    wire c_ovf = ~(&rc[SW-2:V_W-1] | ~|rc[SW-2:V_W-1]);
    wire b_hi = b_ovf & ~rb[SW-2], b_lo = b_ovf & rb[SW-2];
    wire c_hi = c_ovf & ~rc[SW-2], c_lo = c_ovf & rc[SW-2];

    always @(posedge clk) begin
        if (rst) begin
            r_a <= {V_W{1'b0}}; r_b <= {V_W{1'b0}}; w <= {(V_W+1){1'b0}};
            acc <= {AW{1'b0}}; cnt <= {CNT_W{1'b0}}; run <= 1'b0; fin <= 1'b0; busy <= 1'b0;
            r_qb <= {QW{1'b0}}; r_qc <= {QW{1'b0}}; fin2 <= 1'b0;
            u_a <= {V_W{1'b0}}; u_b <= {V_W{1'b0}}; u_c <= {V_W{1'b0}};
            done <= 1'b0; sat <= 1'b0;
        end else begin
            done <= 1'b0;
            sat  <= 1'b0;
            fin  <= 1'b0;
            fin2 <= fin;
            if (start && !busy) begin
                r_a  <= u_alpha;
                r_b  <= u_beta;
                w    <= {{(V_W){1'b0}}, 1'b1} - {u_alpha[V_W-1], u_alpha};
                acc  <= {AW{1'b0}};
                cnt  <= K_BITS[CNT_W-1:0] - 1'b1;
                run  <= 1'b1;
                busy <= 1'b1;
            end
            if (run) begin
                acc <= {acc[AW-2:0], 1'b0} + addend;
                if (cnt == {CNT_W{1'b0}}) begin
                    run <= 1'b0;
                    fin <= 1'b1;
                end else begin
                    cnt <= cnt - 1'b1;
                end
            end
            if (fin) begin
                r_qb <= qb;
                r_qc <= qc;
            end
            if (fin2) begin
                u_a  <= r_a;
                u_b  <= b_hi ? YMAX : b_lo ? YMIN : rb[V_W-1:0];
                u_c  <= c_hi ? YMAX : c_lo ? YMIN : rc[V_W-1:0];
                sat  <= b_hi | b_lo | c_hi | c_lo;
                done <= 1'b1;
                busy <= 1'b0;
            end
        end
    end
endmodule
`default_nettype wire
