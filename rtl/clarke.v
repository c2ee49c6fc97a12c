// clarke: forward Clarke transform of the phase currents (paper 000 eq. 32).
//
//   i_alpha = sat(i_a <<< I_FRAC)
//   i_beta  = sat(((i_b - i_c) * K_BETA + 2^(K_SHIFT-I_FRAC-1)) >>> (K_SHIFT - I_FRAC))
//   K_BETA  = round(2^18 / sqrt(3)) = 151349, K_SHIFT = 18
//   The constant product is computed bit-serially (Horner, MSB first: acc = 2 acc + K[j] d),
//   one adder and no DSP48A1.  Round half up, then saturate.
//   Bit-exact model: gen/empc/rtlmodel/clarke.py.
//   Accuracy: |i_beta - 16 (i_b - i_c)/sqrt(3)| <= 0.55 LSB (Q.4), i_alpha exact.
// Ports:
//   start              1-cycle request; i_a, i_b, i_c sampled in that cycle; ignored while busy
//   i_a, i_b, i_c      signed IN_W-bit offset-corrected ADC currents (ADC LSB, from adc_spi)
//   busy               high from the cycle after start up to the cycle before done
//   done               1-cycle pulse: i_alpha, i_beta, sat updated (held until the next done)
//   i_alpha, i_beta    signed I_W-bit, I_FRAC fractional bits (Q.4 in ADC LSB)
//   sat                1-cycle pulse with done if an output saturated (impossible for IN_W <= 14)
// Parameters: IN_W (default ADC_BITS + 1 = 13), I_W, I_FRAC (empc_formats.vh).
// Latency: done is high K_BITS + 2 = 20 cycles after the start cycle.
// Resources: no DSP, no BRAM; one IN_W+1+18 bit adder plus output rounding.
// Reset: outputs 0, not busy; a conversion in flight is dropped.
`default_nettype none
`include "empc_formats.vh"
module clarke #(
    parameter integer IN_W   = `EMPC_ADC_BITS + 1,
    parameter integer I_W    = `EMPC_I_W,
    parameter integer I_FRAC = `EMPC_I_FRAC
) (
    input  wire                   clk,
    input  wire                   rst,
    input  wire                   start,
    input  wire signed [IN_W-1:0] i_a,
    input  wire signed [IN_W-1:0] i_b,
    input  wire signed [IN_W-1:0] i_c,
    output reg                    busy,
    output reg                    done,
    output reg  signed [I_W-1:0]  i_alpha,
    output reg  signed [I_W-1:0]  i_beta,
    output reg                    sat
);
    localparam integer K_SHIFT = 18;
    localparam integer K_BITS  = 18;
    localparam [K_BITS-1:0] K_BETA = 18'd151349;     // round(2^18 / sqrt(3)), checked by the model test
    localparam integer SH  = K_SHIFT - I_FRAC;         // 14: rounding shift
    localparam integer DW  = IN_W + 1;                 // i_b - i_c
    localparam integer AW  = DW + K_BITS;              // |d * K| < 2^(AW-1)
    localparam integer RW  = AW - SH;                  // rounded i_beta before saturation
    localparam integer XW  = IN_W + I_FRAC;            // i_a << I_FRAC
    localparam integer MW  = (RW > XW) ? RW : XW;
    localparam integer CW  = ((MW > I_W) ? MW : I_W) + 1; // common compare width
    localparam signed [I_W-1:0] YMAX = {1'b0, {(I_W-1){1'b1}}};
    localparam signed [I_W-1:0] YMIN = {1'b1, {(I_W-1){1'b0}}};
    localparam integer CNT_W = $clog2(K_BITS);

    reg signed [DW-1:0]  d;
    reg signed [XW-1:0]  a_sh;
    reg signed [AW-1:0]  acc;
    reg [CNT_W-1:0]      cnt;
    reg                  run, fin;

    wire signed [AW-1:0] d_ext = {{(AW-DW){d[DW-1]}}, d};
    wire signed [AW-1:0] addend = K_BETA[cnt] ? d_ext : {AW{1'b0}};

    // round half up: ((acc >>> (SH-1)) + 1) >>> 1; the lower SH-1 bits cannot carry
    /* verilator lint_off UNUSEDSIGNAL */  // rsum[0] is below the result LSB
    wire signed [RW:0]   rsum = acc[AW-1:SH-1] + {{RW{1'b0}}, 1'b1};
    /* verilator lint_on UNUSEDSIGNAL */
    wire signed [CW-1:0] b_r  = {{(CW-RW){rsum[RW]}}, rsum[RW:1]};
    wire signed [CW-1:0] a_r  = {{(CW-XW){a_sh[XW-1]}}, a_sh};
    // out of range iff the bits from I_W-1 up are not all equal (no comparator needed)
    wire                 b_ovf = ~(&b_r[CW-1:I_W-1] | ~|b_r[CW-1:I_W-1]);
    wire                 a_ovf = ~(&a_r[CW-1:I_W-1] | ~|a_r[CW-1:I_W-1]);
    wire                 b_hi = b_ovf & ~b_r[CW-1], b_lo = b_ovf & b_r[CW-1];
    wire                 a_hi = a_ovf & ~a_r[CW-1], a_lo = a_ovf & a_r[CW-1];

    always @(posedge clk) begin
        if (rst) begin
            d <= {DW{1'b0}}; a_sh <= {XW{1'b0}}; acc <= {AW{1'b0}};
            cnt <= {CNT_W{1'b0}}; run <= 1'b0; fin <= 1'b0; busy <= 1'b0;
            i_alpha <= {I_W{1'b0}}; i_beta <= {I_W{1'b0}}; done <= 1'b0; sat <= 1'b0;
        end else begin
            done <= 1'b0;
            sat  <= 1'b0;
            fin  <= 1'b0;
            if (start && !busy) begin
                d    <= {i_b[IN_W-1], i_b} - {i_c[IN_W-1], i_c};
                a_sh <= {i_a, {I_FRAC{1'b0}}};
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
                i_alpha <= a_hi ? YMAX : a_lo ? YMIN : a_r[I_W-1:0];
                i_beta  <= b_hi ? YMAX : b_lo ? YMIN : b_r[I_W-1:0];
                sat     <= a_hi | a_lo | b_hi | b_lo;
                done    <= 1'b1;
                busy    <= 1'b0;
            end
        end
    end
endmodule
`default_nettype wire
