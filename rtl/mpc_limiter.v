// mpc_limiter: fabric part of the MPC core's circle voltage limiter (model step 6).
//
// The squares and products come from the lanes' multipliers (no DSP here):
//   go (cycle L):  r = u18_d^2 + u18_q^2 (sq_d + sq_q), usq = umax^2 registered
//   L+1:           lim = r > umax^2;  P = index of the highest non-zero bit pair of r
//                  (r = m 4^-z with m in [2^36, 2^38) <=> z = 18 - P)
//   L+2:           RSQRT address m >> 28 = r[2P+1 : 2P-8]  (block RAM, registered read)
//   L+3:           t = RSQRT[m >> 28] valid (the core multiplies umax * t in lane d's mul1)
//   L+5:           ut = umax * t valid;  f = min((umax * t) >> (18 - z), 2^17 - 1)
//                  = min(ut >> P, 2^17 - 1) registered -> valid in L+6.
// lim, P, t and f hold until the next go / ut change.  RSQRT[i] = floor(2^16 / sqrt((i + 1) / 1024))
// (rsqrt.hex written by `empc roms`); bit-exact to limit_circle() in rtlmodel/mpc_core.py.
// Ports: go, sq_d, sq_q, usq (valid with go), ut (umax * t, valid in L+5); lim, t, f (L+6).
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
    input  wire                            go,
    input  wire signed [2*`EMPC_OPW-1:0]   sq_d,
    input  wire signed [2*`EMPC_OPW-1:0]   sq_q,
    input  wire signed [2*`EMPC_OPW-1:0]   usq,
    input  wire signed [2*`EMPC_OPW-1:0]   ut,
    output reg                             lim,
    output reg  signed [`EMPC_OPW-1:0]     t,
    output reg  signed [`EMPC_OPW-1:0]     f
);
    localparam integer OPW = `EMPC_OPW;               // 18
    localparam integer PW  = 2 * OPW;                 // 36: r <= 2^35 fits unsigned in PW bits
    localparam integer RB  = `EMPC_RSQRT_BITS;        // 10
    localparam integer NP  = PW / 2;                  // 18 bit pairs
    localparam integer PB  = 5;                       // pair index 0..17
    localparam integer XW  = PW + RB - 2;             // 44: r with RB-2 zero bits below
    localparam [OPW-1:0] OMAX = {1'b0, {(OPW-1){1'b1}}};

    reg  [OPW-1:0] rom [0:(1<<RB)-1];
    initial $readmemh(RSQRT_FILE, rom);

    reg  [PW:0]   r;            // u18_d^2 + u18_q^2 <= 2^35
    reg  [PW-1:0] usq_r;
    reg  [PB-1:0] pidx;

    // highest non-zero pair of r (0 when r < 4)
    reg  [PB-1:0] pr;
    integer i;
    always @* begin
        pr = {PB{1'b0}};
        for (i = 0; i < NP; i = i + 1)
            if (r[2*i] | r[2*i+1]) pr = i[PB-1:0];
    end

    // RSQRT address = bits [2P+RB-1 : 2P-(RB-2)] of r (zeros below bit 0)
    wire [XW-1:0] rx = {r[PW-1:0], {(RB-2){1'b0}}} >> {pidx, 1'b0};
    wire [RB-1:0] addr = rx[RB-1:0];

    // f = min(ut >> P, 2^17 - 1); ut = umax * t >= 0
    wire [PW-1:0] us = ut >> pidx;
    wire [OPW-1:0] f_c = (|us[PW-1:OPW-1]) ? OMAX : {1'b0, us[OPW-2:0]};

    always @(posedge clk) begin
        if (rst) begin
            r     <= {(PW+1){1'b0}};
            usq_r <= {PW{1'b0}};
            lim   <= 1'b0;
            pidx  <= {PB{1'b0}};
            t     <= {OPW{1'b0}};
            f     <= {OPW{1'b0}};
        end else begin
            if (go) begin
                r     <= {sq_d[PW-1], sq_d} + {sq_q[PW-1], sq_q};
                usq_r <= usq;
            end
            lim  <= (r > {1'b0, usq_r});
            pidx <= pr;
            t    <= rom[addr];
            f    <= f_c;
        end
    end

    wire unused_ok = &{1'b0, r[PW], rx[XW-1:RB]};
endmodule
`default_nettype wire
