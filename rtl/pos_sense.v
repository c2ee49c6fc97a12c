// pos_sense: electrical angle, alignment and speed estimate for NAXES axes (one shared engine)
// (paper 000 sec. V-A "Position Sensing", eq. 37).
//
// Mechanical position modulo CPR, exact and drift free:
//   m = (pos - ref) mod CPR,  0 <= m < CPR,
// where ref is the count at the last alignment event.  m is tracked
// incrementally from the modular difference d = pos - last_pos (exact for any
// movement below 2**(POS_W-1) counts between two looks, so the wrap of the
// 32-bit counter is harmless): a bit-serial reducer adds d mod CPR to m, one bit
// of d per clock (bit k weighs c_k = 2**k mod CPR, a constant table indexed by
// k; m +- c_k and one conditional +-CPR keep m in [0, CPR)).  A +-1 step takes 1
// clock to capture and 1 clock to apply; a jump of any size is applied in at
// most POS_W + 1 clocks; counts arriving meanwhile are picked up by the next
// capture.  At an index event m restarts at 0 and the reducer takes the lag
// pos - index_pos at once (so the counts since the latched index are added).
// No state other than the integer m depends on history, so the angle after N
// whole mechanical turns is bit-identical (also when CPR is not a multiple of P).
//
// Angle (2**ANGLE_BITS = one electrical turn):
//   theta = ( (m * ANGLE_MUL + 2**(S-1)) >> S ) + base       (mod 2**ANGLE_BITS)
//   ANGLE_MUL = round(P * 2**(ANGLE_BITS+S) / CPR)           (constant function)
// S defaults to the largest value <= 24 for which ANGLE_MUL < 2**MUL_W
// (MUL_W = 17: m and ANGLE_MUL are both unsigned 17-bit, one DSP48A1 18x18).
// Error against the exact 2**16 * frac(P*m/CPR) (+ base):
//   |err| <= 0.5 + (CPR-1) * |ANGLE_MUL - P*2**(16+S)/CPR| / 2**S  LSB
//   (default CPR=4000, P=4: S=10, ANGLE_MUL=67109, |err| <= 1.03 LSB =
//   0.0057 deg electrical; so theta is within 1 LSB of round(exact)).
//   The Python model empc.rtlmodel.pos_sense.angle_error_bound() gives the
//   bound for any CPR/P.
//
// Alignment (base and ref):
//   - before the first index, rough HALL alignment: when hall_valid first rises
//     (and nothing is aligned yet): base = centre of the sector, ref = pos.
//     At every later hall_change (still not index-aligned): base = the sector
//     edge just crossed (start of the new sector when moving up 1 sector, end of
//     it when moving down 1 sector, its centre after an implausible jump),
//     ref = pos.  Sector s spans [(s-1)*60, s*60) deg electrical + hall_offset;
//     edge/centre angles are round(k * 2**16 / 12) (k = 0..11).
//   - the first index_event (after reset or align_clear): base = 0,
//     ref = index_pos, aligned = 1; from then on theta = f(m) + cal_offset
//     (cal_offset and hall_offset are live register inputs: a new calibration
//     value acts at once).  HALL changes are ignored while aligned.  Later
//     index events are ignored (REALIGN = 0, default: an index pulse wider
//     than one count latches a direction-dependent count, which must not make
//     theta jump) or re-align every time (REALIGN = 1: repairs lost counts).
//   - align_clear: back to HALL mode (aligned = 0) without a jump of theta:
//     the angle keeps its index reference (theta = f(m) + cal_offset, cal_offset
//     still live) until the next HALL edge (then base = edge + hall_offset) or
//     index re-synchronises.  An index_event in the same clock wins (re-aligns).
//     Without HALL (hall_valid never seen) valid drops to 0 until the index.
//   Priority: index alignment > align_clear > HALL init > HALL change.
//
// Speed (eq. 37, backward difference) and sampling, on the sample strobe:
//   speed           = pos - pos_at_previous_sample, counts per Ts, POS_W-bit
//                     modular difference (exact while |movement| < 2**(POS_W-1)
//                     counts per Ts, so a counter wrap does not disturb it; 0 at
//                     the first sample after reset)
//   speed_q         = speed * 2**W_FRAC saturated to W_W bits (the MPC speed
//                     format, Q16.16 by default); speed_sat = 1 when saturated
//   pos_at_sample   = pos,  theta_at_sample = theta (as output in that clock)
//   sample_valid    one-clock pulse, the clock after sample
// Multi-turn position for the position loop: the raw POS_W-bit count pos
// (modular; use differences).
//
// Ports (NAXES = 1: exactly today's one-axis ports plus theta_ok; NAXES > 1: every
// per-axis port is a vector, axis a at [a*W +: W]):
//   pos[POS_W], index_event, index_pos[POS_W]   from irc_decoder
//   hall_sector[3], hall_valid, hall_change     from hall_decoder
//   cal_offset[16], hall_offset[16]             calibration registers
//   align_clear, sample                          strobes
//   theta[16], valid, aligned, pos_mod[MW]      angle (continuous)
//   theta_ok                                     theta is the final angle of the count pos
//                                                present in this clock (combinational from
//                                                pos: pos != the count in m, the reducer busy
//                                                on the axis or an alignment event clear it;
//                                                offset changes do not, they reach theta
//                                                within the angle latency)
//   speed[POS_W], speed_q[W_W], speed_sat, pos_at_sample[POS_W],
//   theta_at_sample[16], sample_valid           per sample
// Parameters: CPR, POLE_PAIRS, POS_W, ANGLE_BITS, MUL_W, ANGLE_MUL_SHIFT (-1 =
//   auto), W_W, W_FRAC (>= 1), REALIGN (0/1, see above), ANGLE_DSP (1 = the
//   product on a DSP48A1; 0 = m * ANGLE_MUL tracked in fabric next to m, same
//   outputs and latency, about 90 LUTs more, no DSP; NAXES = 1 only), NAXES (1 =
//   today's one-axis datapath; > 1 = the shared engine below), JUMP_W (NAXES = 1: the
//   reducer takes the low JUMP_W bits of pos, index_pos and last_pos and d modulo
//   2**JUMP_W, so it is exact while every jump between two looks, pos - last_pos or
//   pos - index_pos at an index alignment, is in [-2**(JUMP_W-1), 2**(JUMP_W-1)); default
//   POS_W = the full counter.  With irc_decoder's pos (at most one count per clock,
//   index_pos = pos at index_event) a look comes at most JUMP_W + 1 clocks after the last,
//   so any JUMP_W >= 5 is exact: axis_periph's POS_JUMP_W, 8 in mx_axes, about 40 LUTs and
//   48 FFs less than 32).  MW = clog2(CPR).
//   2 <= CPR < 2**17 keeps the product in one DSP (larger works, more DSPs).
// Latency (NAXES = 1): pos step -> pos_mod 2 clocks (+1 per extra bit of a jump);
//   pos_mod -> theta 2 clocks (DSP M register, then the DSP post-adder adds
//   the offset and the rounding constant into the P register = theta);
//   a +-1 count reaches theta 4 clocks after pos (theta_ok 4 clocks after the last
//   change).  valid/aligned are delayed with theta.  sample -> speed/... 1 clock.
//
// NAXES > 1, one shared engine (per-axis state in flip-flops: m, last_pos, the
// latched index count, alignment / HALL state, base ROM address, theta, about 110
// bits per axis without the speed outputs):
//   - the reducer visits the axes in the fixed order 0, 1, ..., NAXES-1, 0, ...: a
//     visit of axis a captures d = pos[a] - last_pos[a] (pos[a] - index_pos[a] once
//     after an index alignment); no work (pos = last_pos, no index pending) costs
//     one clock, a job one clock per bit of d (at most POS_W), and the next visit is
//     captured in the clock of the job's last bit.  Same c_k ROM and reducer as above.
//   - alignment events act in their own clock on their axis alone (m = 0, base,
//     last_pos = pos at a HALL event, index_pos latched at an index alignment); a job
//     of that axis in flight ends.  Same priorities and angles as NAXES = 1.
//   - the angle pipeline samples one axis per clock, round robin (m, HALL-angle ROM
//     read, offset), then m * ANGLE_MUL (DSP M), + base * 2**S + 2**(S-1) (DSP P),
//     and writes theta / valid / aligned of that axis 4 clocks after the sample; a
//     tag (axis not dirty before any of the 4 edges) sets theta_ok.
//   - latency, count change of axis a -> theta_ok[a] (tb/test_pos_sense_naxes.py):
//     all axes jump at once, from an idle engine: <= NAXES*POS_W + NAXES + 4 clocks
//     (136 at NAXES = 4, POS_W = 32; measured worst 135; design figure 134); any
//     situation (the engine may have just captured a's previous count): <=
//     (NAXES+1)*POS_W + NAXES + 4 (168; measured 165).  A +-1 step of one axis: 8..11
//     clocks (NAXES = 4).  An offset change reaches theta within NAXES + 4 clocks.
// Reset: m = 0, not aligned, no HALL init, theta valid = 0, theta_ok = 0, speed 0.
// Resources (Yosys synth_xilinx xc6s, OOC): NAXES = 1: 1 DSP48A1, 1 RAMB8BWER (the
//   c_k and HALL angle tables as a ROM), 198 FFs, 218 LUTs (215 / 196 with theta_ok
//   open; ~130 LUTs / ~98 FFs when the speed/sample outputs are left open, as in
//   mpc_axis).  NAXES = 4: 1 DSP48A1, 1 RAMB8BWER, 946 FFs, 766 LUTs (409 LUTs /
//   546 FFs with the per-axis speed/sample outputs open).
`default_nettype none
`include "empc_formats.vh"
module pos_sense #(
    parameter integer CPR = `EMPC_ENC_CPR,
    parameter integer POLE_PAIRS = `EMPC_POLE_PAIRS,
    parameter integer POS_W = `EMPC_POS_W,
    parameter integer ANGLE_BITS = `EMPC_ANGLE_BITS,
    parameter integer MUL_W = 17,
    parameter integer ANGLE_MUL_SHIFT = -1,
    parameter integer W_W = `EMPC_W_W,
    parameter integer W_FRAC = `EMPC_W_FRAC,
    parameter integer REALIGN = 0,
    parameter integer ANGLE_DSP = 1,
    parameter integer NAXES = 1,
    parameter integer JUMP_W = POS_W      // NAXES = 1: bits of the jump d the reducer takes (see the header)
) (
    input  wire                          clk,
    input  wire                          rst,
    input  wire [NAXES*POS_W-1:0]        pos,
    input  wire [NAXES-1:0]              index_event,
    input  wire [NAXES*POS_W-1:0]        index_pos,
    input  wire [NAXES*3-1:0]            hall_sector,
    input  wire [NAXES-1:0]              hall_valid,
    input  wire [NAXES-1:0]              hall_change,
    input  wire [NAXES*ANGLE_BITS-1:0]   cal_offset,
    input  wire [NAXES*ANGLE_BITS-1:0]   hall_offset,
    input  wire [NAXES-1:0]              align_clear,
    input  wire [NAXES-1:0]              sample,
    output wire [NAXES*ANGLE_BITS-1:0]   theta,
    output wire [NAXES-1:0]              valid,
    output wire [NAXES-1:0]              aligned,
    output wire [NAXES-1:0]              theta_ok,
    output wire [NAXES*MW-1:0]           pos_mod,
    output wire [NAXES*POS_W-1:0]        speed,
    output wire [NAXES*W_W-1:0]          speed_q,
    output wire [NAXES-1:0]              speed_sat,
    output wire [NAXES*POS_W-1:0]        pos_at_sample,
    output wire [NAXES*ANGLE_BITS-1:0]   theta_at_sample,
    output wire [NAXES-1:0]              sample_valid
);

    // ---------------- constants ----------------
    function integer clog2;
        input integer v;
        integer t;
        begin
            clog2 = 0;
            t = v - 1;
            while (t > 0) begin
                clog2 = clog2 + 1;
                t = t >> 1;
            end
        end
    endfunction

    function integer clog2_64;
        input [63:0] v;
        reg [63:0] t;
        begin
            clog2_64 = 0;
            t = v - 64'd1;
            while (t > 64'd0) begin
                clog2_64 = clog2_64 + 1;
                t = t >> 1;
            end
        end
    endfunction

    // round(p * 2**(ab+s) / cpr), round half up
    function [63:0] calc_mul;
        input integer cpr;
        input integer p;
        input integer ab;
        input integer s;
        reg [63:0] num;
        reg [63:0] den;
        begin
            num = 64'd0;
            num[31:0] = p;
            num = num << (ab + s);
            den = 64'd0;
            den[31:0] = cpr;
            calc_mul = (2 * num + den) / (2 * den);
        end
    endfunction

    // largest s <= 24 with calc_mul(...) < 2**mul_w
    function integer auto_shift;
        input integer cpr;
        input integer p;
        input integer ab;
        input integer mul_w;
        integer s;
        reg [63:0] lim;
        begin
            auto_shift = 0;
            lim = 64'd1 << mul_w;
            for (s = 0; s <= 24; s = s + 1)
                if (calc_mul(cpr, p, ab, s) < lim) auto_shift = s;
        end
    endfunction

    localparam integer MW = (clog2(CPR) < 1) ? 1 : clog2(CPR);       // m in [0, CPR)
    localparam integer S = (ANGLE_MUL_SHIFT < 0) ? auto_shift(CPR, POLE_PAIRS, ANGLE_BITS, MUL_W)
                                                 : ANGLE_MUL_SHIFT;
    localparam [63:0] MUL64 = calc_mul(CPR, POLE_PAIRS, ANGLE_BITS, S);
    localparam integer MULB = (clog2_64(MUL64 + 64'd1) < 1) ? 1 : clog2_64(MUL64 + 64'd1);
    localparam [MULB-1:0] MUL = MUL64[MULB-1:0];
    localparam integer PROD_W = MW + MULB;
    localparam [MW:0] CPR_C = CPR[MW:0];

    // HALL angles round(j * 2**ANGLE_BITS / 12) mod 2**ANGLE_BITS (j = 0..11), indexed by
    // {sector, kind}: sector s (1..6) starts at j = 2s-2 (kind 0), its centre is j = 2s-1
    // (kind 1), it ends at j = 2s mod 12 (kind 2); other entries 0
    function [32*ANGLE_BITS-1:0] hall_tab;
        input integer dummy;
        integer sec, kd;
        reg [63:0] v;
        begin
            hall_tab = {(32*ANGLE_BITS){1'b0}};
            for (sec = 1; sec <= 6; sec = sec + 1)
                for (kd = 0; kd < 3; kd = kd + 1) begin
                    v = 64'd0;
                    v[31:0] = (2 * sec - 2 + kd + dummy) % 12;
                    v = ((v << ANGLE_BITS) + 64'd6) / 64'd12;
                    hall_tab[(sec*4+kd)*ANGLE_BITS +: ANGLE_BITS] = v[ANGLE_BITS-1:0];
                end
        end
    endfunction
    localparam [32*ANGLE_BITS-1:0] HALL_TAB = hall_tab(0);
    function [2:0] s_next; input [2:0] sec; s_next = (sec == 3'd6) ? 3'd1 : sec + 3'd1; endfunction

    // C_TAB[k] = 2**k mod CPR, k = 0..POS_W-1: the weight of bit k of a jump
    /* verilator lint_off UNUSEDSIGNAL */ // v < CPR: only its low MW bits
    function [POS_W*MW-1:0] pow_tab;
        input integer dummy;
        integer j;
        reg [63:0] v, cpr64;
        begin
            pow_tab = {(POS_W*MW){1'b0}};
            cpr64 = 64'd0;
            cpr64[31:0] = CPR + dummy;
            v = 64'd1 % cpr64;
            for (j = 0; j < POS_W; j = j + 1) begin
                pow_tab[j*MW +: MW] = v[MW-1:0];
                v = (2 * v) % cpr64;
            end
        end
    endfunction
    /* verilator lint_on UNUSEDSIGNAL */
    localparam [POS_W*MW-1:0] C_TAB = pow_tab(0);
    localparam integer KW = (clog2(POS_W) < 1) ? 1 : clog2(POS_W);

    // Both tables in one block RAM (ROM, two read ports, registered outputs), so that
    // neither costs LUTs: C_TAB at addresses 0.. (port B, read with the next k: c is the
    // entry of the current k); at 2**TA + {hall_init, last_sector, sector} the HALL angle
    // of a HALL event in that state (port A: its output register is base_rel, loaded at a
    // HALL event and cleared by the index / align_clear).  The kind of angle: the centre
    // at HALL init (hall_init = 0), else the edge crossed (start of the new sector moving
    // up one sector, its end moving down one), the centre after a jump.
    localparam integer TW = (MW > ANGLE_BITS) ? MW : ANGLE_BITS;       // ROM word
    localparam integer HA = 7;                                          // {hall_init, last_sector, sector}
    localparam integer TA = (KW > HA) ? KW : HA;                        // address = {half, TA bits}
    localparam [TA:0]  HALL_BASE = {1'b1, {TA{1'b0}}};
    (* rom_style = "block" *) reg [TW-1:0] trom [0:2*(2**TA)-1];
    integer ti;
    reg [2:0] t_hs, t_ls;
    reg [1:0] t_kd;
    initial begin
        for (ti = 0; ti < 2 * (2**TA); ti = ti + 1) trom[ti] = {TW{1'b0}};
        for (ti = 0; ti < POS_W; ti = ti + 1) trom[ti][MW-1:0] = C_TAB[ti*MW +: MW];
        for (ti = 0; ti < 2**HA; ti = ti + 1) begin
            t_hs = ti[2:0];
            t_ls = ti[5:3];
            t_kd = (ti < 2**(HA-1)) ? 2'd1 : (t_hs == s_next(t_ls)) ? 2'd0 : (t_ls == s_next(t_hs)) ? 2'd2 : 2'd1;
            trom[2**TA + ti][ANGLE_BITS-1:0] = HALL_TAB[{t_hs, t_kd}*ANGLE_BITS +: ANGLE_BITS];
        end
    end

    // ---------------- reducer datapath shared by both variants ----------------
    // RW: the reducer's width (NAXES = 1: JUMP_W, the low bits of the counts; NAXES > 1: POS_W)
    localparam integer RW = (NAXES == 1) ? JUMP_W : POS_W;
    reg  [RW-1:0]        r;          // remaining jump (signed), shifted right per clock
    reg  [KW-1:0]        k;          // bit of the jump in r[0]: weight 2**k
    reg                  busy;
    wire                 load;       // r <= d this clock (per variant)
    wire [MW-1:0]        m_cur;      // m of the axis the reducer works on
    wire [RW-1:0] r_sh = {r[RW-1], r[RW-1:1]};
    // r[RW-1:1] all 0 or all 1 = r[RW-2:1] all equal to the sign r[RW-1]: groups of
    // UGS bits (one LUT6 each with the sign), ANDed on a carry chain (carry out of +1)
    localparam integer UGS = 5;
    localparam integer UG = (RW - 2 + UGS - 1) / UGS;
    localparam integer UEW = (UGS * UG + 1 > RW) ? UGS * UG + 1 : RW;
    /* verilator lint_off UNUSEDSIGNAL */ // bit 0 and the top sign copies (padding) unused
    wire [UEW-1:0] r_ext = {{(UEW - RW + 1){r[RW-1]}}, r[RW-2:0]};
    /* verilator lint_on UNUSEDSIGNAL */
    wire [UG-1:0]  r_gu;
    genvar gi;
    generate
        for (gi = 0; gi < UG; gi = gi + 1) begin : g_uni
            assign r_gu[gi] = (r_ext[UGS*gi+1 +: UGS] == {UGS{r[RW-1]}});
        end
    endgenerate
    wire [UG:0] r_unc = {1'b0, r_gu} + {{UG{1'b0}}, 1'b1};
    wire r_uni = r_unc[UG];                     // r[RW-1:1] is 0 or -1
    wire r_neg1 = r_uni & r[RW-1] & r[0];    // remainder -1: subtract 2**k, done
    wire r_done = r_uni & (~r[RW-1] | r[0]); // last bit of the jump
    // m +- c (c = 2**k mod CPR), then back into [0, CPR): + CPR if negative (subtract),
    // - CPR if >= CPR (add).  s is in (-CPR, 2*CPR); the reduced value's top bit is 0.
    // c = C_TAB[k]: ROM port B read with k's next value
    wire [KW-1:0] k_nx = (rst || load) ? {KW{1'b0}} : k + 1'b1;
    /* verilator lint_off UNUSEDSIGNAL */ // ROM word bits above MW
    reg  [TW-1:0] c_r;
    /* verilator lint_on UNUSEDSIGNAL */
    always @(posedge clk) c_r <= trom[{{(TA+1-KW){1'b0}}, k_nx}];
    wire [MW-1:0] c = c_r[MW-1:0];
    wire [MW+1:0] s = {2'b0, m_cur} + ({2'b0, c} ^ {(MW+2){r_neg1}}) + {{(MW+1){1'b0}}, r_neg1};
    wire s_neg = s[MW+1];
    wire s_ge = !s_neg && (s[MW:0] >= CPR_C);
    /* verilator lint_off UNUSEDSIGNAL */
    wire [MW:0] s_red = s[MW:0] + (s_neg ? CPR_C : s_ge ? -CPR_C : {(MW+1){1'b0}});
    /* verilator lint_on UNUSEDSIGNAL */

    // ---------------- angle constants ----------------
    // Both variants give theta(t+2) = ((m(t) * ANGLE_MUL + 2**(S-1)) >> S) + base_d(t+1)
    // (mod 2**ANGLE_BITS); only the low S + ANGLE_BITS bits of the product matter.
    localparam integer ACC_W = S + ANGLE_BITS;
    localparam integer MP_W = (PROD_W > ACC_W) ? PROD_W : ACC_W;   // DSP M register
    localparam [ACC_W-1:0] HALF = (S > 0) ? ({{(ACC_W-1){1'b0}}, 1'b1} << (S - 1)) : {ACC_W{1'b0}};
    // step of m * ANGLE_MUL for the DSP-free angle (ANGLE_DSP = 0): S_TAB[2k + corr] =
    // c_k * ANGLE_MUL - corr * CPR * ANGLE_MUL (mod 2**ACC_W)
    /* verilator lint_off UNUSEDSIGNAL */ // w: only the low ACC_W bits (mod 2**ACC_W)
    function [2*POS_W*ACC_W-1:0] stab;
        input integer dummy;
        integer j, cr;
        reg [63:0] v, w, cpr64, mul64;
        begin
            stab = {(2*POS_W*ACC_W){1'b0}};
            cpr64 = 64'd0;
            cpr64[31:0] = CPR + dummy;
            mul64 = MUL64;
            v = 64'd1 % cpr64;
            for (j = 0; j < POS_W; j = j + 1) begin
                for (cr = 0; cr < 2; cr = cr + 1) begin
                    w = v * mul64 - ((cr != 0) ? cpr64 * mul64 : 64'd0);
                    stab[(2*j+cr)*ACC_W +: ACC_W] = w[ACC_W-1:0];
                end
                v = (2 * v) % cpr64;
            end
        end
    endfunction
    /* verilator lint_on UNUSEDSIGNAL */
    /* verilator lint_off UNUSEDPARAM */ // used only without the DSP (ANGLE_DSP = 0)
    localparam [2*POS_W*ACC_W-1:0] S_TAB = stab(0);
    /* verilator lint_on UNUSEDPARAM */

    generate
    if (NAXES == 1) begin : g_one
    // ================= one axis: the reducer and the angle pipeline of that axis alone =================
    reg [RW-1:0]      last_pos;   // count already handed to the reducer
    reg [MW-1:0]         m;          // (pos - ref) mod CPR
    reg                  al;         // index aligned (internal, leads the output by 2 clocks)
    reg                  rel_cal;    // not aligned, but base_rel is relative to cal_offset (align_clear)
    reg                  hall_init;
    reg [2:0]            last_sector;
    /* verilator lint_off UNUSEDSIGNAL */ // ROM word bits above ANGLE_BITS
    reg [TW-1:0]         base_r;     // ROM port A: angle added to f(m), relative to the offset in use
    /* verilator lint_on UNUSEDSIGNAL */
    wire [ANGLE_BITS-1:0] base_rel = base_r[ANGLE_BITS-1:0];
    reg                  valid_r, aligned_r;

    assign pos_mod = m;
    assign m_cur = m;
    assign valid = valid_r;
    assign aligned = aligned_r;

    // ---------------- alignment events ----------------
    wire ev_hall_init = !al && !hall_init && hall_valid[0];
    wire ev_hall_chg  = !al && hall_init && hall_valid[0] && hall_change[0];
    wire ev_hall = ev_hall_init || ev_hall_chg;
    // ROM address of the HALL angle (hall_init = 0 there at the HALL init event)
    wire [TA:0] hall_addr = HALL_BASE | {{(TA+1-HA){1'b0}}, hall_init, last_sector, hall_sector};
    // index alignment: the first index after reset / align_clear (every index if REALIGN)
    wire ev_index = index_event[0] && (!al || align_clear[0] || (REALIGN != 0));
    wire ev_any = ev_index || ev_hall;

    // ---------------- bit-serial modular accumulation ----------------
    // d: the new counts (pos - last_pos), or at an index event the lag pos - index_pos
    // (m restarts at 0 = index_pos and the reducer adds the counts since the index)
    // JUMP_W < POS_W: the low JUMP_W bits of the counts, d modulo 2**JUMP_W (exact while every jump
    // between two looks is below 2**(JUMP_W-1) counts, header)
    wire [RW-1:0] pos_j = pos[RW-1:0];
    wire [RW-1:0] d_ref = ev_index ? index_pos[RW-1:0] : last_pos;
    wire [RW-1:0] d = pos_j - d_ref;
    wire          unused_jump = &{1'b0, index_pos};    // bits above JUMP_W (JUMP_W < POS_W)
    // d == 0 without an OR tree over d: pos ~^ d_ref (the subtractor's own propagate LUTs)
    // all ones, as the carry out of +1 on a carry chain
    wire [RW:0]   d_eqc = {1'b0, pos_j ~^ d_ref} + {{RW{1'b0}}, 1'b1};
    wire             d_zero = d_eqc[RW];
    assign load = !busy || ev_any;              // r <= d (ignored when d = 0 or at a HALL event)
    always @(posedge clk) begin
        if (rst || ev_index || (align_clear[0] && al))
            base_r <= {TW{1'b0}};
        else if (ev_hall)
            base_r <= trom[hall_addr];
    end

    always @(posedge clk) begin
        if (rst) begin
            last_pos    <= {RW{1'b0}};
            r           <= {RW{1'b0}};
            k           <= {KW{1'b0}};
            m           <= {MW{1'b0}};
            busy        <= 1'b0;
            al          <= 1'b0;
            rel_cal     <= 1'b0;
            hall_init   <= 1'b0;
            last_sector <= 3'd0;
        end else begin
            // reducer
            if (load) begin
                last_pos <= pos_j;
                r        <= d;
            end else begin
                r        <= r_sh;
            end
            if (load) k <= {KW{1'b0}};
            else      k <= k + 1'b1;
            if (ev_any)
                m <= {MW{1'b0}};
            else if (busy && r[0])
                m <= s_red[MW-1:0];
            if (ev_hall && !ev_index)
                busy <= 1'b0;
            else if (load)
                busy <= !d_zero;
            else if (r_done)
                busy <= 1'b0;

            // alignment state
            // (base_rel: ROM port A above, same priority)
            if (ev_index) begin
                al       <= 1'b1;
            end else if (align_clear[0] && al) begin
                al       <= 1'b0;
                rel_cal  <= 1'b1;
            end else if (ev_hall) begin
                rel_cal  <= 1'b0;
            end
            if (hall_valid[0] && (!hall_init || hall_change[0])) begin
                hall_init   <= 1'b1;
                last_sector <= hall_sector;
            end
        end
    end

    // ---------------- theta_ok ----------------
    // dirty: counts not yet applied (pos != last_pos, or the reducer busy) or an alignment
    // event in this clock.  theta after clock t+2 is f(state before t+1), so theta is final
    // when the state was clean before the last two edges and still is (see the header).
    wire dirty = !d_zero || busy || ev_any;
    reg  ok1, okq;
    always @(posedge clk) begin
        if (rst) begin
            ok1 <= 1'b0;
            okq <= 1'b0;
        end else begin
            ok1 <= !dirty;
            okq <= ok1 && !dirty;
        end
    end
    assign theta_ok = okq && !dirty;

    // ---------------- angle pipeline ----------------
    reg  [ANGLE_BITS-1:0] base_d;
    // base_rel + offset as {base_rel, 0} - {~offset, 1} (>> 1): the offset multiplexer then
    // folds into the adder's LUTs (base_rel, the ROM output, is the carry chain's DI)
    wire [ANGLE_BITS-1:0] off_sel = (al || rel_cal) ? cal_offset : hall_offset;
    /* verilator lint_off UNUSEDSIGNAL */ // bit 0 is the carry-in position only
    wire [ANGLE_BITS:0]   base_sum = {base_rel, 1'b0} - {~off_sel, 1'b1};
    /* verilator lint_on UNUSEDSIGNAL */
    reg                   v1, al1;
    always @(posedge clk) begin
        if (rst) begin
            base_d    <= {ANGLE_BITS{1'b0}};
            v1        <= 1'b0;
            al1       <= 1'b0;
            valid_r   <= 1'b0;
            aligned_r <= 1'b0;
        end else begin
            base_d    <= base_sum[ANGLE_BITS:1];
            v1        <= al | hall_init;
            al1       <= al;
            valid_r   <= v1;
            aligned_r <= al1;
        end
    end

        if (ANGLE_DSP != 0) begin : g_dsp
            // mprod = m * ANGLE_MUL (DSP M register), acc = mprod + base_d * 2**S + 2**(S-1)
            // (DSP post-adder, P register): theta = acc[S +: ANGLE_BITS]
            /* verilator lint_off UNUSEDSIGNAL */ // product bits >= ACC_W are whole turns, acc bits < S rounding only
            reg  [MP_W-1:0]  mprod;
            reg  [ACC_W-1:0] acc;
            /* verilator lint_on UNUSEDSIGNAL */
            reg  [ACC_W-1:0] base_s;
            always @* begin
                base_s = HALF;
                base_s[S +: ANGLE_BITS] = base_d;
            end
            wire [MP_W-1:0]  m_mul = m * MUL;
            always @(posedge clk) begin
                if (rst) begin
                    mprod <= {MP_W{1'b0}};
                    acc   <= {ACC_W{1'b0}};
                end else begin
                    mprod <= m_mul;
                    acc   <= mprod[ACC_W-1:0] + base_s;
                end
            end
            assign theta = acc[S +: ANGLE_BITS];
        end else begin : g_nodsp
            // No multiplier: a = m * ANGLE_MUL + 2**(S-1) (mod 2**ACC_W) is tracked next to m,
            // one clock behind it.  Every step of m (+-c_k, then -+CPR) moves a by
            // +-(c_k * ANGLE_MUL - corr * CPR * ANGLE_MUL): a table indexed by k and the
            // reducer's correction bit, registered, then one add/subtract.
            wire             corr = r_neg1 ? s_neg : s_ge;      // the reducer added +-CPR
            wire             step = busy && r[0] && !ev_any;    // m changes by +-c_k (mod CPR)
            reg  [ACC_W-1:0] sv;                                // the step of a, magnitude
            reg              sv_sub, sv_on, a_clr;
            reg  [ACC_W-1:0] a;
            reg  [ANGLE_BITS-1:0] th;
            // a +- sv in one adder: the LSB pair (1, sv_sub) injects the carry-in (a_n[0] unused)
            /* verilator lint_off UNUSEDSIGNAL */
            wire [ACC_W:0] a_n = {a, 1'b1} + {sv ^ {ACC_W{sv_sub}}, sv_sub};
            /* verilator lint_on UNUSEDSIGNAL */
            always @(posedge clk) begin
                if (rst) begin
                    sv     <= {ACC_W{1'b0}};
                    sv_sub <= 1'b0;
                    sv_on  <= 1'b0;
                    a_clr  <= 1'b0;
                    a      <= HALF;
                    th     <= {ANGLE_BITS{1'b0}};
                end else begin
                    sv     <= S_TAB[{k, corr}*ACC_W +: ACC_W];
                    sv_sub <= r_neg1;
                    sv_on  <= step;
                    a_clr  <= ev_any;
                    if (a_clr)
                        a <= HALF;
                    else if (sv_on)
                        a <= a_n[ACC_W:1];
                    th     <= a[S +: ANGLE_BITS] + base_d;
                end
            end
            assign theta = th;
        end
    end else begin : g_mx
    // ================= NAXES axes, one shared engine =================
    // Per-axis state in flip-flops (g_ax[a]); the reducer (r, k, busy, cur) and the angle
    // pipeline (one DSP48A1) serve one axis at a time through axis multiplexers.
    localparam integer AW = (clog2(NAXES) < 1) ? 1 : clog2(NAXES);
    localparam integer LASTI = NAXES - 1;
    localparam [AW-1:0] LAST = LASTI[AW-1:0];
    localparam integer HW = TA + 1;                                     // ROM address width
    localparam [HW-1:0] ZERO_A = {1'b0, {TA{1'b1}}};                    // a ROM word that is 0
    localparam integer PG = (POS_W + 2) / 3;                            // 3-bit groups of a count
    // per-axis state, flattened (axis a at [a*W +: W]) for the multiplexers
    wire [NAXES*POS_W-1:0]      lp_w, ip_w;
    wire [NAXES*MW-1:0]         m_w;
    wire [NAXES*HW-1:0]         ha_w;
    wire [NAXES-1:0]            ipend_w, ucal_w, vin_w, al_w;
    wire [NAXES-1:0]            ev_any, dirty, pend_w;
    // engine
    reg  [AW-1:0]  cur;                                     // axis of the reducer's job / last visit
    wire [AW-1:0]  nxt = (cur == LAST) ? {AW{1'b0}} : cur + 1'b1;
    wire [POS_W-1:0] pos_n = pos[nxt*POS_W +: POS_W];
    wire [POS_W-1:0] ref_n = ipend_w[nxt] ? ip_w[nxt*POS_W +: POS_W] : lp_w[nxt*POS_W +: POS_W];
    wire [POS_W-1:0] d = pos_n - ref_n;
    // work for the visited axis: new counts (the per-axis comparator of theta_ok), or an index
    // alignment (a job even when the lag pos - index_pos is 0: one clock)
    wire             work = pend_w[nxt] || ipend_w[nxt];
    // the job ends: its last bit, or an alignment event of its axis (which restarts m)
    wire fin = busy && (r_done || ev_any[cur]);
    assign load = !busy || fin;                             // visit the next axis
    assign m_cur = m_w[cur*MW +: MW];
    always @(posedge clk) begin
        if (rst) begin
            cur  <= LAST;
            r    <= {POS_W{1'b0}};
            k    <= {KW{1'b0}};
            busy <= 1'b0;
        end else if (load) begin
            cur  <= nxt;
            r    <= d;
            k    <= {KW{1'b0}};
            busy <= work && !ev_any[nxt];
        end else begin
            r    <= r_sh;
            k    <= k + 1'b1;
        end
    end

    genvar ga;
    for (ga = 0; ga < NAXES; ga = ga + 1) begin : g_ax
        localparam integer AI = ga;
        localparam [AW-1:0] A = AI[AW-1:0];
        wire [POS_W-1:0] pos_a = pos[ga*POS_W +: POS_W];
        reg  [POS_W-1:0] lp;            // count handed to the reducer
        reg  [POS_W-1:0] ip;            // index count of the last index alignment
        reg              ipend;         // the reducer still has to add pos - ip (m restarted at the index)
        reg  [MW-1:0]    m;
        reg              al, rel_cal, hall_init;
        reg  [2:0]       last_sector;
        reg  [HW-1:0]    ha;            // ROM address of base_rel: a HALL angle, or ZERO_A
        wire ev_hall = !al && hall_valid[ga] && (!hall_init || hall_change[ga]);
        wire ev_index = index_event[ga] && (!al || align_clear[ga] || (REALIGN != 0));
        wire eng_ld = load && (nxt == A);
        wire eng_wr = busy && (cur == A) && r[0];
        assign ev_any[ga] = ev_index || ev_hall;
        // pos_a != lp: groups of 3 bit pairs (one LUT6 each), ANDed on a carry chain
        wire [PG-1:0]    eq_g;
        wire [3*PG-1:0]  pos_x = {{(3*PG-POS_W){1'b0}}, pos_a};
        wire [3*PG-1:0]  lp_x = {{(3*PG-POS_W){1'b0}}, lp};
        genvar gq;
        for (gq = 0; gq < PG; gq = gq + 1) begin : g_eq
            assign eq_g[gq] = (pos_x[3*gq +: 3] == lp_x[3*gq +: 3]);
        end
        wire [PG:0]      eq_c = {1'b0, eq_g} + {{PG{1'b0}}, 1'b1};
        assign pend_w[ga] = !eq_c[PG];
        assign dirty[ga] = ipend || pend_w[ga] || (busy && (cur == A)) || ev_index || ev_hall;
        assign lp_w[ga*POS_W +: POS_W] = lp;
        assign ip_w[ga*POS_W +: POS_W] = ip;
        assign ipend_w[ga] = ipend;
        assign m_w[ga*MW +: MW] = m;
        assign ha_w[ga*HW +: HW] = ha;
        assign ucal_w[ga] = al || rel_cal;
        assign vin_w[ga] = al || hall_init;
        assign al_w[ga] = al;
        assign pos_mod[ga*MW +: MW] = m;
        always @(posedge clk) begin
            if (rst) begin
                lp          <= {POS_W{1'b0}};
                ip          <= {POS_W{1'b0}};
                ipend       <= 1'b0;
                m           <= {MW{1'b0}};
                al          <= 1'b0;
                rel_cal     <= 1'b0;
                hall_init   <= 1'b0;
                last_sector <= 3'd0;
                ha          <= ZERO_A;
            end else begin
                if (ev_hall || eng_ld)
                    lp <= pos_a;
                if (ev_index)
                    ip <= index_pos[ga*POS_W +: POS_W];
                if (ev_index)
                    ipend <= 1'b1;
                else if (ev_hall || eng_ld)
                    ipend <= 1'b0;
                if (ev_index || ev_hall)
                    m <= {MW{1'b0}};
                else if (eng_wr)
                    m <= s_red[MW-1:0];
                if (ev_index) begin
                    al      <= 1'b1;
                end else if (align_clear[ga] && al) begin
                    al      <= 1'b0;
                    rel_cal <= 1'b1;
                end else if (ev_hall) begin
                    rel_cal <= 1'b0;
                end
                if (hall_valid[ga] && (!hall_init || hall_change[ga])) begin
                    hall_init   <= 1'b1;
                    last_sector <= hall_sector[3*ga +: 3];
                end
                if (ev_index || (align_clear[ga] && al))
                    ha <= ZERO_A;
                else if (ev_hall)
                    ha <= HALL_BASE | {{(TA+1-HA){1'b0}}, hall_init, last_sector, hall_sector[3*ga +: 3]};
            end
        end
    end

    // ---------------- angle pipeline, round robin over the axes ----------------
    // X: sample axis ap (m, ROM read of the base, offset); X+1: m * ANGLE_MUL (DSP M), base +
    // offset; X+2: + base * 2**S + 2**(S-1) (DSP P); X+3: theta[axis] and valid/aligned of the
    // sample.  A tag travels with the sample: "clean" = the axis was not dirty before any of the
    // four edges, so theta is final (theta_ok).
    reg  [AW-1:0]         ap;
    reg  [MW-1:0]         mb;
    /* verilator lint_off UNUSEDSIGNAL */ // ROM word bits above ANGLE_BITS; product bits >= ACC_W, acc bits < S
    reg  [TW-1:0]         hq;
    reg  [MP_W-1:0]       mprod;
    reg  [ACC_W-1:0]      acc;
    /* verilator lint_on UNUSEDSIGNAL */
    reg  [ANGLE_BITS-1:0] calq, hallq, base_d;
    reg                   ucq;
    reg  [AW-1:0]         a1, a2, a3;
    reg                   c1, c2, c3, v1, v2, v3, l1, l2, l3;
    wire [AW-1:0]         ap_nx = (ap == LAST) ? {AW{1'b0}} : ap + 1'b1;
    reg  [ACC_W-1:0]      base_s;
    always @* begin
        base_s = HALF;
        base_s[S +: ANGLE_BITS] = base_d;
    end
    wire [MP_W-1:0] m_mul = mb * MUL;
    // base + offset as {base, 0} - {~offset, 1} (>> 1), the cal / hall select folded into
    // the adder's LUTs (as for NAXES = 1)
    wire [ANGLE_BITS-1:0] off_sel = ucq ? calq : hallq;
    /* verilator lint_off UNUSEDSIGNAL */ // bit 0 is the carry-in position only
    wire [ANGLE_BITS:0]   base_sum = {hq[ANGLE_BITS-1:0], 1'b0} - {~off_sel, 1'b1};
    /* verilator lint_on UNUSEDSIGNAL */
    always @(posedge clk) hq <= trom[ha_w[ap*HW +: HW]];
    always @(posedge clk) begin
        if (rst) begin
            ap     <= {AW{1'b0}};
            mb     <= {MW{1'b0}};
            calq   <= {ANGLE_BITS{1'b0}};
            hallq  <= {ANGLE_BITS{1'b0}};
            ucq    <= 1'b0;
            base_d <= {ANGLE_BITS{1'b0}};
            mprod  <= {MP_W{1'b0}};
            acc    <= {ACC_W{1'b0}};
            a1 <= {AW{1'b0}}; a2 <= {AW{1'b0}}; a3 <= {AW{1'b0}};
            c1 <= 1'b0; c2 <= 1'b0; c3 <= 1'b0;
            v1 <= 1'b0; v2 <= 1'b0; v3 <= 1'b0;
            l1 <= 1'b0; l2 <= 1'b0; l3 <= 1'b0;
        end else begin
            ap     <= ap_nx;
            mb     <= m_w[ap*MW +: MW];
            calq   <= cal_offset[ap*ANGLE_BITS +: ANGLE_BITS];
            hallq  <= hall_offset[ap*ANGLE_BITS +: ANGLE_BITS];
            ucq    <= ucal_w[ap];
            a1     <= ap;
            c1     <= !dirty[ap];
            v1     <= vin_w[ap];
            l1     <= al_w[ap];
            mprod  <= m_mul;
            base_d <= base_sum[ANGLE_BITS:1];
            a2     <= a1;
            c2     <= c1 && !dirty[a1];
            v2     <= v1;
            l2     <= l1;
            acc    <= mprod[ACC_W-1:0] + base_s;
            a3     <= a2;
            c3     <= c2 && !dirty[a2];
            v3     <= v2;
            l3     <= l2;
        end
    end
    for (ga = 0; ga < NAXES; ga = ga + 1) begin : g_out
        localparam integer AI = ga;
        localparam [AW-1:0] A = AI[AW-1:0];
        reg [ANGLE_BITS-1:0] th;
        reg                  vq, alq, okq;
        always @(posedge clk) begin
            if (rst) begin
                th  <= {ANGLE_BITS{1'b0}};
                vq  <= 1'b0;
                alq <= 1'b0;
                okq <= 1'b0;
            end else if (a3 == A) begin
                th  <= acc[S +: ANGLE_BITS];
                vq  <= v3;
                alq <= l3;
                okq <= c3 && !dirty[ga];
            end else begin
                okq <= okq && !dirty[ga];
            end
        end
        assign theta[ga*ANGLE_BITS +: ANGLE_BITS] = th;
        assign valid[ga] = vq;
        assign aligned[ga] = alq;
        assign theta_ok[ga] = okq && !dirty[ga];
    end
    end
    endgenerate

    // ---------------- speed (eq. 37) and sampling, per axis ----------------
    localparam integer WIDE = POS_W + W_FRAC;
    localparam [W_W-1:0] QMAX = {1'b0, {(W_W-1){1'b1}}};
    localparam [W_W-1:0] QMIN = {1'b1, {(W_W-1){1'b0}}};
    genvar gs;
    generate
        for (gs = 0; gs < NAXES; gs = gs + 1) begin : g_spd
            wire [POS_W-1:0] pos_a = pos[gs*POS_W +: POS_W];
            reg  [POS_W-1:0]      sp, pas;
            reg  [W_W-1:0]        spq;
            reg                   ssat, sv, have_prev;
            reg  [ANGLE_BITS-1:0] tas;
            wire [POS_W-1:0] diff = pos_a - pas;
            wire [WIDE-1:0]  wide = {diff, {W_FRAC{1'b0}}};
            wire [WIDE-W_W:0] top = wide[WIDE-1:W_W-1];
            wire fits = (&top) | ~(|top);
            always @(posedge clk) begin
                if (rst) begin
                    sp        <= {POS_W{1'b0}};
                    spq       <= {W_W{1'b0}};
                    ssat      <= 1'b0;
                    pas       <= {POS_W{1'b0}};
                    tas       <= {ANGLE_BITS{1'b0}};
                    sv        <= 1'b0;
                    have_prev <= 1'b0;
                end else begin
                    sv <= sample[gs];
                    if (sample[gs]) begin
                        have_prev <= 1'b1;
                        pas       <= pos_a;
                        tas       <= theta[gs*ANGLE_BITS +: ANGLE_BITS];
                        if (have_prev) begin
                            sp   <= diff;
                            spq  <= fits ? wide[W_W-1:0] : (diff[POS_W-1] ? QMIN : QMAX);
                            ssat <= !fits;
                        end else begin
                            sp   <= {POS_W{1'b0}};
                            spq  <= {W_W{1'b0}};
                            ssat <= 1'b0;
                        end
                    end
                end
            end
            assign speed[gs*POS_W +: POS_W] = sp;
            assign speed_q[gs*W_W +: W_W] = spq;
            assign speed_sat[gs] = ssat;
            assign pos_at_sample[gs*POS_W +: POS_W] = pas;
            assign theta_at_sample[gs*ANGLE_BITS +: ANGLE_BITS] = tas;
            assign sample_valid[gs] = sv;
        end
    endgenerate

`ifndef SYNTHESIS
    initial begin
        if (CPR < 2) $display("ERROR: pos_sense CPR=%0d < 2", CPR);
        if (W_FRAC < 1 || WIDE < W_W) $display("ERROR: pos_sense needs W_FRAC >= 1 and POS_W + W_FRAC >= W_W");
        if (NAXES < 1) $display("ERROR: pos_sense NAXES=%0d < 1", NAXES);
        if (NAXES > 1 && ANGLE_DSP == 0) $display("ERROR: pos_sense NAXES > 1 needs ANGLE_DSP = 1");
        if (JUMP_W < 5 || JUMP_W > POS_W || (NAXES > 1 && JUMP_W != POS_W))
            $display("ERROR: pos_sense JUMP_W=%0d: 5..POS_W, and POS_W when NAXES > 1", JUMP_W);
        if (NAXES > 1 && POS_W >= 2**TA) $display("ERROR: pos_sense NAXES > 1 needs POS_W < %0d (a zero ROM word)", 2**TA);
    end
`endif
endmodule
`default_nettype wire
