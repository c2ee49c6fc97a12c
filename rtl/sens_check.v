// sens_check: HALL-vs-encoder plausibility and encoder line-break detection for one axis.
//
// Two checks, both with thresholds a healthy drive cannot reach at any speed (the HALL and
// encoder latencies are constant, so they cancel in differences; docs/blocks/sens_check.md):
//
// 1. Angle (continuous, every clock while theta_valid and hall_valid): the sector of the
//    encoder angle, j = floor(6 (theta - hall_offset) / 2^16) on the top 8 bits (1.4 deg
//    quantisation), is compared with the HALL sector s; `hall_enc` when they are 2 or 3
//    sectors apart (circular).  Tolerance one sector (60 deg electrical) for the HALL edge
//    placement and calibration error and the HALL debounce lag (0.7 deg at 1200 rad/s).
//    A stuck HALL while the encoder turns, a swapped HALL pair (4 of 6 sectors read 2
//    sectors off once index-aligned), a wrong ANGLE_CAL or lost counts of more than one
//    sector trip it.
// 2. HALL edges (at every hall_change): dpos = pos - pos at the previous HALL change
//    (DW-bit modular difference), step = new sector - previous sector (mod 6):
//      step not +-1 (a sector skipped)                              -> hall_enc
//      step +1 with dpos < -S_LO, or -1 with dpos > +S_LO (the HALL
//        moves against the encoder by more than half a sector)       -> hall_enc
//      step in the same direction as the previous step (the rotor crossed a whole sector,
//      edge to edge, healthy width S = CPR / (6 P) counts):
//        |dpos| < S_LO (encoder counts missing: line break, a dead channel dithers the
//        count by +-1)                                               -> enc_break
//        |dpos| > S_HI (HALL edge missed or extra counts)            -> hall_enc
//    S_LO = round(S/2), S_HI = round(3S/2): each HALL edge may be up to a quarter sector
//    (15 deg electrical) off its nominal place.  A direction reversal crosses the same
//    edge twice (|dpos| = HALL hysteresis, small): only the "against" rule applies to it.
//    The first HALL change after reset (or after a jump) has no previous step: only the
//    jump and "against" rules.
//
// Ports: clk, rst; theta_hi[8] (top bits of pos_sense theta, continuous), theta_valid,
//   hall_off_hi[8] (top bits of HALL_OFFSET, the HALL sector-1 start), hall_sector[3], hall_valid, hall_change
//   (hall_decoder), pos[DW] (low DW bits of the encoder count); hall_enc, enc_break
//   (registered, one clock per event; hall_enc from check 1 is a level while it holds).
// Parameters: CPR, POLE_PAIRS (as pos_sense), DW (width of dpos: S_HI < 2^(DW-1)).
// Latency: 1 clock from the inputs (a HALL edge: from hall_change; the angle: from theta).
// Reset: no reference (the first legal HALL sector after reset sets it), outputs 0.
// Resources: about 25 flip-flops and 50 LUTs.
`default_nettype none
`include "empc_formats.vh"
module sens_check #(
    parameter integer CPR = `EMPC_ENC_CPR,
    parameter integer POLE_PAIRS = `EMPC_POLE_PAIRS,
    parameter integer DW = 16
) (
    input  wire          clk,
    input  wire          rst,
    input  wire [7:0]    theta_hi,
    input  wire          theta_valid,
    input  wire [7:0]    hall_off_hi,
    input  wire [2:0]    hall_sector,
    input  wire          hall_valid,
    input  wire          hall_change,
    input  wire [DW-1:0] pos,
    output reg           hall_enc,
    output reg           enc_break
);
    localparam integer S_LO = (CPR + 6 * POLE_PAIRS) / (12 * POLE_PAIRS);        // round(S / 2)
    localparam integer S_HI = (3 * CPR + 6 * POLE_PAIRS) / (12 * POLE_PAIRS);    // round(3 S / 2)
    generate if (S_LO < 1 || S_HI >= (1 << (DW - 1))) begin : g_bad_params
        sens_check_unsupported_parameters u_error ();   // no such module: elaboration stops here
    end endgenerate
    localparam [31:0] SL = S_LO, SH = S_HI, NSL = 32'd0 - SL, NSH = 32'd0 - SH;
    localparam signed [DW-1:0] P_LO = SL[DW-1:0], N_LO = NSL[DW-1:0], P_HI = SH[DW-1:0], N_HI = NSH[DW-1:0];

    // ---- check 1: sector of the encoder angle against the HALL sector ----
    wire [7:0] rel = theta_hi - hall_off_hi;
    // j = floor(6 rel / 256): boundaries 42.7, 85.3, 128, 170.7, 213.3
    wire [2:0] j = (rel >= 8'd214) ? 3'd5 : (rel >= 8'd171) ? 3'd4 : (rel >= 8'd128) ? 3'd3 :
                   (rel >= 8'd86) ? 3'd2 : (rel >= 8'd43) ? 3'd1 : 3'd0;
    // circular distance of HALL sector s (1..6) and j + 1: sd = (s - 1 - j) mod 6 (a function
    // of 6 bits: one LUT6); far = distance 2 or 3 = sd in 2..4
    wire [3:0] sd = ({1'b0, hall_sector} + 4'd5 - {1'b0, j}) % 4'd6;
    wire       far = (hall_sector != 3'd0) && (hall_sector != 3'd7) && (sd >= 4'd2) && (sd <= 4'd4);

    // ---- check 2: encoder movement between HALL edges ----
    reg          have;                  // reference sector / count taken
    reg  [2:0]   s_last;
    reg  [DW-1:0] pos_ref;
    reg          lst_fwd, lst_bwd;      // direction of the previous +-1 step
    wire [3:0]   dstep = ({1'b0, hall_sector} + 4'd6 - {1'b0, s_last}) % 4'd6;
    wire         fwd = (dstep == 4'd1);
    wire         bwd = (dstep == 4'd5);
    wire signed [DW-1:0] dpos = pos - pos_ref;
    wire         against = (fwd && dpos < N_LO) || (bwd && dpos > P_LO);
    wire         same = (fwd && lst_fwd) || (bwd && lst_bwd);
    wire         short = same && (fwd ? (dpos < P_LO) : (dpos > N_LO));
    wire         long = same && (fwd ? (dpos > P_HI) : (dpos < N_HI));
    wire         ev = hall_change && hall_valid && have;

    always @(posedge clk) begin
        if (rst) begin
            have      <= 1'b0;
            s_last    <= 3'd0;
            pos_ref   <= {DW{1'b0}};
            lst_fwd   <= 1'b0;
            lst_bwd   <= 1'b0;
            hall_enc  <= 1'b0;
            enc_break <= 1'b0;
        end else begin
            hall_enc  <= (theta_valid && hall_valid && far) || (ev && (!(fwd || bwd) || against || long));
            enc_break <= ev && short;
            if (hall_valid && (!have || hall_change)) begin
                have    <= 1'b1;
                s_last  <= hall_sector;
                pos_ref <= pos;
                lst_fwd <= have && fwd;
                lst_bwd <= have && bwd;
            end
        end
    end
endmodule
`default_nettype wire
