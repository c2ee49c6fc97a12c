// sens_check: HALL-vs-encoder plausibility and encoder line-break detection for one axis.
//
// Two checks, both with thresholds a healthy drive cannot reach at any speed (the HALL and
// encoder latencies are constant, so they cancel in differences; docs/blocks/sens_check.md):
//
// 1. Angle (continuous, every clock while theta_valid and hall_valid): the sector of the
//    encoder angle, j = floor(6 (theta - hall_offset) / 2^16) on the top 6 bits (5.6 deg
//    quantisation), registered, is compared with the HALL sector s (registered with it);
//    `hall_enc` when they are 2 or 3 sectors apart (circular), 2 clocks after the inputs.  Tolerance one sector (60 deg electrical) for the HALL edge
//    placement and calibration error and the HALL debounce lag (0.7 deg at 1200 rad/s).
//    A stuck HALL while the encoder turns, a swapped HALL pair (4 of 6 sectors read 2
//    sectors off once index-aligned), a wrong ANGLE_CAL or lost counts of more than one
//    sector trip it.
// 2. HALL edges (at every hall_change): dq = pos[DW-1:QS] - the same at the previous HALL
//    change ((DW-QS)-bit modular difference in units of 2^QS counts: 8 counts, 3 % of a
//    sector by default), step = new sector - previous sector (mod 6):
//      step not +-1 (a sector skipped)                              -> hall_enc
//      step +1 with dq < -S_LO, or -1 with dq >= +S_LO (the HALL
//        moves against the encoder by about half a sector)           -> hall_enc
//      step in the same direction as the previous step (the rotor crossed a whole sector,
//      edge to edge, healthy width S = CPR / (6 P) counts):
//        +1: dq < S_LO, -1: dq >= -S_LO (encoder counts missing: line break, a dead
//        channel dithers the count by +-1)                           -> enc_break
//        +1: dq >= S_HI, -1: dq < -S_HI (HALL edge missed or extra counts) -> hall_enc
//    S_LO = the power of two at or below S / 2, S_HI = the power of two at or above 3 S / 2,
//    in units (8 and 32 units = 64 and 256 counts by default, S = 166.7 counts: 0.38 S and
//    1.54 S; powers of two make the compares bit tests): each HALL edge may be up to 13 deg
//    electrical off its nominal place (two same-direction edges 34..86 deg apart = 94..239
//    counts), the units add one (8 counts) at most.  A direction reversal crosses the same
//    edge twice (|dq| = HALL hysteresis, small): only the "against" rule applies to it.
//    The first HALL change after reset (or after a jump) has no previous step: only the
//    jump and "against" rules.
//
// Ports: clk, rst; theta_hi[6] (top bits of pos_sense theta, continuous), theta_valid,
//   hall_off_hi[6] (top bits of HALL_OFFSET, the HALL sector-1 start), hall_sector[3], hall_valid, hall_change
//   (hall_decoder), pos_q[DW-QS] (encoder count bits DW-1..QS); hall_enc, enc_break
//   (registered, one clock per event; hall_enc from check 1 is a level while it holds).
// Parameters: CPR, POLE_PAIRS (as pos_sense), DW (low count bits used), QS (unit = 2^QS
//   counts; S_HI < 2^(DW-QS-2)).
// Latency: a HALL edge: 1 clock from hall_change; the angle check: 2 clocks from theta.
// Reset: no reference (the first legal HALL sector after reset sets it), outputs 0.
// Resources: 24 flip-flops, about 45 LUTs.
`default_nettype none
`include "empc_formats.vh"
module sens_check #(
    parameter integer CPR = `EMPC_ENC_CPR,
    parameter integer POLE_PAIRS = `EMPC_POLE_PAIRS,
    parameter integer DW = 12,
    parameter integer QS = 3
) (
    input  wire          clk,
    input  wire          rst,
    input  wire [5:0]    theta_hi,
    input  wire          theta_valid,
    input  wire [5:0]    hall_off_hi,
    input  wire [2:0]    hall_sector,
    input  wire          hall_valid,
    input  wire          hall_change,
    input  wire [DW-QS-1:0] pos_q,         // encoder count bits DW-1 .. QS
    output reg           hall_enc,
    output reg           enc_break
);
    localparam integer UW = DW - QS;                                             // width of dq
    localparam integer U = 1 << QS;                                              // counts per unit
    // thresholds: powers of two bracketing half and 1.5 sector widths (S = CPR / (6 P) counts),
    // in units: S_LO = 2^LL <= S / 2 / U, S_HI = 2^LH >= 3 S / 2 / U; every compare with them
    // is a bit test (no carry chain)
    function integer log2_floor;
        input integer v;
        begin
            log2_floor = 0;
            while ((2 << log2_floor) <= v) log2_floor = log2_floor + 1;
        end
    endfunction
    function integer log2_ceil;
        input integer v;
        begin
            log2_ceil = 0;
            while ((1 << log2_ceil) < v) log2_ceil = log2_ceil + 1;
        end
    endfunction
    localparam integer LL = log2_floor(CPR / (12 * POLE_PAIRS * U));
    localparam integer LH = log2_ceil((3 * CPR + 12 * POLE_PAIRS * U - 1) / (12 * POLE_PAIRS * U));
    generate if (CPR / (12 * POLE_PAIRS * U) < 2 || LH > UW - 3 || QS < 0) begin : g_bad_params
        sens_check_unsupported_parameters u_error ();   // no such module: elaboration stops here
    end endgenerate

    // 6-input tables (one LUT6 per output bit): j of a 6-bit angle, and for two sectors a, b
    // (1..6): FWD (b follows a), BWD (b precedes a), FAR (the sector a and the encoder sector
    // index b (0..5) are 2 or 3 apart)
    /* verilator lint_off UNUSEDSIGNAL */ // v < 6: only its low 3 bits
    function [191:0] j_tab;
        input integer dummy;
        integer r;
        reg [31:0] v;
        begin
            j_tab = 192'd0;
            for (r = 0; r < 64; r = r + 1) begin
                v = (6 * r + dummy) / 64;
                j_tab[3 * r +: 3] = v[2:0];
            end
        end
    endfunction
    /* verilator lint_on UNUSEDSIGNAL */
    function [63:0] rel_tab;                        // kind 0 FWD, 1 BWD, 2 FAR
        input integer kind;
        integer a, b, d;
        begin
            rel_tab = 64'd0;
            for (a = 1; a <= 6; a = a + 1)
                for (b = 0; b <= 6; b = b + 1) begin
                    d = (kind == 2) ? (a - 1 - b + 12) % 6 : (b - a + 12) % 6;
                    if ((kind == 0 && b >= 1 && d == 1) || (kind == 1 && b >= 1 && d == 5) ||
                        (kind == 2 && b <= 5 && d >= 2 && d <= 4))
                        rel_tab[8 * a + b] = 1'b1;
                end
        end
    endfunction
    localparam [191:0] J_TAB = j_tab(0);
    localparam [63:0]  FWD_TAB = rel_tab(0), BWD_TAB = rel_tab(1), FAR_TAB = rel_tab(2);

    // ---- check 1: sector of the encoder angle against the HALL sector (two stages) ----
    wire [5:0] rel = theta_hi - hall_off_hi;
    wire [2:0] j = J_TAB[3 * rel +: 3];             // floor(6 rel / 64)
    reg  [2:0] j_r, s_r;
    reg        v_r;
    wire       far = v_r && FAR_TAB[{s_r, j_r}];

    // ---- check 2: encoder movement between HALL edges, in units of 2^QS counts ----
    reg          have;                  // reference sector / count taken
    reg  [2:0]   s_last;
    reg  [UW-1:0] pos_ref;
    reg          lst_fwd, lst_bwd;      // direction of the previous +-1 step
    wire         fwd = FWD_TAB[{s_last, hall_sector}];
    wire         bwd = BWD_TAB[{s_last, hall_sector}];
    wire [UW-1:0] dq = pos_q - pos_ref;
    wire [UW-1:0] ndq = ~dq;            // -dq - 1: dq < -2^k <=> ndq >= 2^k
    // x >= 2^k for a UW-bit signed x: not negative and a bit set in [UW-2:k]
    wire         p_lo = !dq[UW-1] && (|dq[UW-2:LL]);      // dq >= S_LO
    wire         n_lo = !ndq[UW-1] && (|ndq[UW-2:LL]);    // dq < -S_LO
    wire         p_hi = !dq[UW-1] && (|dq[UW-2:LH]);      // dq >= S_HI
    wire         n_hi = !ndq[UW-1] && (|ndq[UW-2:LH]);    // dq < -S_HI
    wire         against = (fwd && n_lo) || (bwd && p_lo);
    wire         same = (fwd && lst_fwd) || (bwd && lst_bwd);
    wire         short = same && (fwd ? !p_lo : !n_lo);
    wire         long = same && (fwd ? p_hi : n_hi);
    wire         ev = hall_change && hall_valid && have;

    always @(posedge clk) begin
        if (rst) begin
            j_r       <= 3'd0;
            s_r       <= 3'd0;
            v_r       <= 1'b0;
            have      <= 1'b0;
            s_last    <= 3'd0;
            pos_ref   <= {UW{1'b0}};
            lst_fwd   <= 1'b0;
            lst_bwd   <= 1'b0;
            hall_enc  <= 1'b0;
            enc_break <= 1'b0;
        end else begin
            j_r       <= j;
            s_r       <= hall_sector;
            v_r       <= theta_valid && hall_valid;
            hall_enc  <= far || (ev && (!(fwd || bwd) || against || long));
            enc_break <= ev && short;
            if (hall_valid && (!have || hall_change)) begin
                have    <= 1'b1;
                s_last  <= hall_sector;
                pos_ref <= pos_q;
                lst_fwd <= have && fwd;
                lst_bwd <= have && bwd;
            end
        end
    end
endmodule
`default_nettype wire
