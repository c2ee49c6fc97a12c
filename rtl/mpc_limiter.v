// mpc_limiter: fabric part of the MPC core's circle voltage limiter (model step 6).
//
// The squares, r = u18_d^2 + u18_q^2 and r - umax^2 are formed in lane d's multiplier and
// accumulator, umax * t in lane d's mul1 (sequenced by mpc_core); this block holds the rest:
//   ld_r (cycle L, acc = r):    r, P = index of the highest non-zero bit pair of r registered
//                               (r = m 4^-z with m in [2^36, 2^38) <=> z = 18 - P)
//   L+1:                        RSQRT address m >> 28 = r[2P+1 : 2P-8] (zeros below bit 0)
//   L+2:                        t = RSQRT[m >> 28] valid (block RAM, registered read)
//   ld_lim (acc = r - umax^2):  lim = acc > 0 registered
//   f = (ut >> P)[16:0] (combinational; ut = umax * t >= 0).  The model's min(., 2^17 - 1)
//   never binds when lim = 1: t <= 2^35 / sqrt(m) gives ut >> P < 2^17 umax / sqrt(r) < 2^17;
//   when lim = 0, f is not used.
// RSQRT[i] = floor(2^16 / sqrt((i + 1) / 1024)) (rsqrt.hex written by `empc roms`);
// bit-exact to limit_circle() in rtlmodel/mpc_core.py.
// Field-weakening flags (model step 7), from the registered r (valid from L+1 until the next
// ld_r): fw_hi = r[35:20] > fw_thr_hi, fw_lo = r[35:20] < fw_thr_lo (combinational).
// Ports: acc (lane d accumulator), ld_r, ld_lim, ut (lane d mul1), fw_thr_hi / lo (register
// FW_R2); lim, t (L+2), f, fw_hi, fw_lo.
// Parameters: RSQRT_FILE ($readmemh file, RSQRT_BITS address bits, 18-bit words).
// Latency: see above (fixed).  Resources: 1 RAMB16 (1024 x 18), no DSP.
// Reset: registers clear to 0 (the ROM contents are constant).
`default_nettype none
`include "empc_formats.vh"
module mpc_limiter #(
    parameter RSQRT_FILE = "rsqrt.hex"
) (
    input  wire                            clk,
    input  wire                            rst,
    input  wire signed [`EMPC_ACCW-1:0]    acc,
    input  wire                            ld_r,
    input  wire                            ld_lim,
    input  wire signed [`EMPC_ACCW-1:0]    ut,
    input  wire [15:0]                     fw_thr_hi,
    input  wire [15:0]                     fw_thr_lo,
    output wire                            fw_hi,
    output wire                            fw_lo,
    output reg                             lim,
    output reg  signed [`EMPC_OPW-1:0]     t,
    output wire signed [`EMPC_OPW-1:0]     f
);
    localparam integer OPW = `EMPC_OPW;               // 18
    localparam integer PW  = 2 * OPW;                 // 36: r <= 2^35 fits unsigned in PW bits
    localparam integer RB  = `EMPC_RSQRT_BITS;        // 10
    localparam integer NP  = PW / 2;                  // 18 bit pairs
    localparam integer PB  = 5;                       // pair index 0..17
    localparam integer XW  = PW + RB - 2;             // 44: r with RB-2 zero bits below

    reg  [OPW-1:0] rom [0:(1<<RB)-1];
    initial $readmemh(RSQRT_FILE, rom);

    reg  [PW-1:0] r;
    reg  [PB-1:0] pidx;

    // highest non-zero pair of acc (0 when acc < 4)
    reg  [PB-1:0] pr;
    integer i;
    always @* begin
        pr = {PB{1'b0}};
        for (i = 0; i < NP; i = i + 1)
            if (acc[2*i] | acc[2*i+1]) pr = i[PB-1:0];
    end

    // RSQRT address = bits [2P+RB-1 : 2P-(RB-2)] of r (zeros below bit 0); 2P = 8 P[4:2] + 2 P[1:0]
    wire [XW+3:0]  rz = {4'd0, r, {(RB-2){1'b0}}};
    reg  [RB+5:0]  w1;                  // rz >> 8 P[4:2]
    always @* begin
        case (pidx[4:2])
            3'd0:    w1 = rz[RB+5:0];
            3'd1:    w1 = rz[8 +: RB+6];
            3'd2:    w1 = rz[16 +: RB+6];
            3'd3:    w1 = rz[24 +: RB+6];
            default: w1 = rz[32 +: RB+6];
        endcase
    end
    wire [RB-1:0] addr = w1[{1'b0, pidx[1:0], 1'b0} +: RB];

    // f = ut >> P (< 2^17 when lim); P = 4 P[4:2] + P[1:0]
    reg  [OPW+1:0] x1;                  // ut >> 4 P[4:2]
    always @* begin
        case (pidx[4:2])
            3'd0:    x1 = ut[OPW+1:0];
            3'd1:    x1 = ut[4 +: OPW+2];
            3'd2:    x1 = ut[8 +: OPW+2];
            3'd3:    x1 = ut[12 +: OPW+2];
            default: x1 = ut[16 +: OPW+2];
        endcase
    end
    wire [OPW-2:0] fs = x1[{3'b0, pidx[1:0]} +: OPW-1];
    assign f = {1'b0, fs};

    // field-weakening band (r < 2^36: r[35:20] is 16 bit)
    assign fw_hi = r[PW-1:PW-16] > fw_thr_hi;
    assign fw_lo = r[PW-1:PW-16] < fw_thr_lo;

    // acc = r - umax^2 in (-2^34, 2^35]: bit PW is its sign
    wire gt0 = ~acc[PW] & (|acc[PW:0]);

    always @(posedge clk) begin
        if (rst) begin
            r    <= {PW{1'b0}};
            pidx <= {PB{1'b0}};
            lim  <= 1'b0;
            t    <= {OPW{1'b0}};
        end else begin
            if (ld_r) begin
                r    <= acc[PW-1:0];
                pidx <= pr;
            end
            if (ld_lim) lim <= gt0;
            t <= rom[addr];
        end
    end

    wire unused_ok = &{1'b0, acc[`EMPC_ACCW-1:PW+1], ut[`EMPC_ACCW-1:PW]};
endmodule
`default_nettype wire
