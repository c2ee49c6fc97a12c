// ref_gen: reference generator (paper 000 sec. V-A): time-parameterised
// polynomial segments evaluated once per control period by exact integer
// forward differences (no multipliers), on a bit-serial engine.
//
// 16 segment slots in one block RAM, written and read by the CPU one 32-bit
// field at a time (port A: seg_we / seg_re, slot seg_slot, field seg_field:
// 0 len, 1 r0[31:0], 2 r0[63:32], 3 d1[31:0], 4 d1[63:32], 5 d2, 6 flags):
//   len   [31:0]  control periods (0 = the segment never ends)
//   r0    [63:0]  start value, Q.32 of the output unit (32 integer + 32 fraction bits)
//   d1    [63:0]  first forward difference per period, Q.32
//   d2    [31:0]  signed second forward difference per period, Q.32
//   flags [1:0]   bit 0 relative: start from the current value instead of r0;
//                 bit 1 last: hold at the end of this segment (else go on with slot + 1 mod 16)
// A write lands at once (no staging: the CPU must not rewrite a slot that an advance
// may load meanwhile, i.e. the active slot's successor or a pending start slot).
// State: head (= w_{k+N}), d1, d2, remaining, and the active segment's "ends"
// (len != 0), "last" and slot number.  Per executed advance:
//   h1 = head + d1; d1' = d1 + sext(d2); remaining' = remaining - 1 (if the segment ends)
//   - start pending: load slot start_slot
//   - else remaining == 1 (the segment ends now) and last: hold: head = h1, d1 = d2 = 0,
//     no further end
//   - else remaining == 1: load slot (slot + 1) mod 16
//   - else head = h1, d1 = d1', remaining = remaining'
//   load(s): head = relative[s] ? h1 : r0[s]; d1, d2, remaining = d1[s], d2[s], len[s]
// `sync` sets head and the whole delay line to the sync value (read bit by bit through
// sync_idx / sync_bit while the sync runs), zero differences, hold
// (a pending start survives a sync).
// Operations are queued and executed one at a time by the engine: advance, start
// and sync strobes set pending flags; when idle the engine runs a pending sync
// first, then a pending advance (several advance strobes before it runs count once).
// A start is taken by the first advance that begins after it (a start in the clock
// an advance begins stays pending for the next one).
// Engine (one bit per clock, LSB first; every pass has one lead clock for the block
// RAM's read latency):
//   advance, no load:  one 64-clock pass: the new head bit (h1 = head + d1, or h1 with
//                      d1 = 0 for a hold) is shifted into the delay line while d1, d2
//                      and remaining are updated in the same pass
//   advance with load: flags (2 clocks), head pass (64: h1 or r0 from the RAM), then
//                      d1 (64), d2 (32), len (32) read from the RAM into the state
//   governor enabled:  the head pass writes rt, and passes G1..G5 (64 each) follow it (before
//                      d1 / d2 / len of a load); G4 shifts the delay line, G5 updates V, B
//   sync:              N+1 passes of 64: the sync value (also into rt; v = 0), then N copies
//                      of the head
// Delay line: w_k .. w_{k+N} in one shift register ((N+1)*64 bits, SRL LUT-RAM): each
// pass shifts in a new head word; the old head is read at a fixed tap (bit 63).
// Readout: rd_q = bit rd_bit of w_{k+N-rd_age} (combinational, any time w_ok = 1).
// Arithmetic is modular 2^64 (no saturation): for a position unit (encoder counts)
// the integer part wraps modulo 2^32 like the encoder counter, by design, and
// consumers take differences modulo 2^32 of the integer part; for a speed unit
// (counts per Ts) the CPU must keep the profile within +-2^31 counts/Ts.
// Reference governor (issue 15 item 4; gen/empc/governor.py, rtlmodel/ref_gen.gov_step):
// enabled (field 7 of slot 4, bit 0), the profile above runs on the target r (register rt)
// and the delay line receives the governed g: after the head pass (r_old -> r_new) four
// passes compute, in 64-bit two's complement with the 65th bit tracked for the clamps,
//   G1: vd = (r_new - r_old) + ((r_old - g) >>> ksh), compared with +-vmax; braking zones
//   G2: dv = clamp(vd, +-vmax) [0 in the speed task when hold and vd would raise |g|; 0 in the
//       position task in the brake zone] - v
//   G3: dv compared with +-a
//   G4: v = v + clamp(dv, +-a) [0 in the position task when hold or in the no-speed-up zone and dv
//       would raise |v|], g = g + v shifted into the delay line; |v| compared with V and V - a
//   G5: V, B updated
// Braking distance (position task, issue 15; rtlmodel/ref_gen.brake_zone / brake_update): per axis
// V = n a (n = ceil(|v| / a), tracked one step per advance: up when |v'| > V, down when |v'| + a <= V)
// and B = a n (n + 1) / 2 (B += V' up, B -= V down), adds only; the distance a reference at |v| <= V
// travels while braking at a.  When the target holds (r_new = r_old) and v moves towards it
// (v != 0, sign(v) = sign(e), e = r_old - g): |e| < B brakes (vd = 0: dv = -a), |e| < B + 2V allows
// no speed-up; G1 computes |e| - B and |e| - (B + 2V) (sign bits, mod 2^64).  A sync and a head pass
// without the governor clear V and B with v.
// vmax, a: field 7 of slots 0/1 and 2/3 (63 bit: bit 63 reads as 0), ksh: field 7 of slot 4,
// bits 12:8.  hold and task_pos are taken when an advance begins; gov_ev pulses at the end
// of G4 when a clamp or the hold changed the reference.  Disabled: g = r, v = 0.
// Speed-task hold, one-sided (issue 15 item 6): vd passes unless it would raise |g|, i.e.
// vd = 0 unless g != 0 and sign(vd) != sign(g) (sign of the exact 65-bit vd; g = 0: every vd
// raises |g|).  The head pass latches g != 0 (g_nz) and g's sign bit (g_sgn) from the tap, G1
// decides at bit 63 (hblk), G2 applies it.  (Until then the speed hold set vd = 0 both ways:
// on the voltage limit the reference then could not come down with the target: spmsm_002 at
// box corner_b, field weakening, RMS speed error 8.2 % of the top, now 0.6 %;
// docs/field_weakening.md.)
//
// Axes (parameter NAXES = 1..4): every axis has its own slots, state, delay line and
// pending flags; one engine runs the operations of all axes, one at a time.  When idle it
// begins the pending sync of the lowest-numbered axis, else the pending advance of the
// lowest-numbered axis (fixed order; an axis's operation may wait for another axis's).  An
// operation reads and writes only its own axis's state: the slot memory is one block RAM
// {axis, slot, field, bit} (16 Kbit at 4 axes); the delay line is a shift register (SRL) per
// axis, shifted only by an operation of its axis; d1, d2, remaining, the governor's rt, v, the
// braking state V, B and a copy of the head are one block RAM {axis, bit} (8 bits wide) read and
// written bit-serially by the engine (NAXES = 1: rt, v, V, B SRLs, d1, d2, remaining flip-flops);
// ends, last, remaining == 1, slot
// and the governor's enable / ksh are a LUT-RAM {axis}; sa, sb and the engine's counters and
// carries are shared scratch (empty between operations).  The CPU port and the readout take
// the axis in the high bits of seg_slot and rd_age; the axis's strobes, sync value, hold /
// task and w_ok, busy, gov_ev are bit a of per-axis vectors.  At NAXES = 1 the ports and the
// timing are those of the one-axis block.
//
// Ports (a = axis, 0 .. NAXES-1; AXB = clog2(NAXES), 0 at NAXES = 1):
//   clk, rst                  clock, synchronous active-high reset
//   seg_we, seg_re, seg_slot[AXB+3:0] = {axis, slot}, seg_field[2:0], seg_wdata[31:0]
//                             CPU field write / read of the slot memory
//   seg_rdata[31:0]           field read, valid the clock after seg_re (0 in other clocks);
//                             flags read back as written in bits 1:0, the rest 0
//   start[a], start_slot[4a+3:4a]  begin axis a's profile at start_slot at its next advance
//   sync[a]                   set all of axis a's outputs to the sync value, zero differences, hold
//   sync_idx[5:0], sync_bit[a] the sync value of axis a, bit by bit: sync_bit[a] = bit sync_idx
//                             of it (combinational; it must stay constant until busy[a] falls)
//   advance[a]                pulse once per control period of axis a
//   rd_age[AXB+AW-1:0] = {axis, age}, rd_bit[5:0], rd_q
//                             reference readout (age 0 = w_{k+N} .. N = w_k), valid while the
//                             axis's w_ok is 1 (also while the engine runs another axis)
//   w_ok[a]                   axis a's delay line is current: no sync or advance of a is pending
//                             or shifting (an advance with a load is done with the delay line
//                             after its head pass)
//   busy[a]                   an operation of axis a is running or pending
//   hold[a], task_pos[a]      governor hold and task of axis a, taken when its advance begins
//   gov_ev[a]                 pulse: the governor changed axis a's reference (end of G4)
// Parameters:
//   N                         prediction horizon (delay line N+1 deep), >= 1
//   NAXES                     axes, 1..4 (AW, AXB: derived widths, leave at their defaults)
// Latency (per axis, engine idle): advance strobe -> w_ok: 66 clocks (no load), 69 (load; busy
//   199), with the governor 326 / 329 (busy 390 / 524: G5 after the delay line); sync -> w_ok (N+1)*65 + 1 clocks.
//   An operation that finds the engine busy with another axis waits for it (at most one
//   operation per other axis with an advance pending, or all their pending syncs).  Consumers
//   wait for w_ok.
// Reset: differences 0, hold, no start/advance pending; every delay line (no reset pins) is
//   cleared by a sync to 0: axis 0's starts with rst, the other axes' queue behind it (busy[a]
//   for about (a+1)*(N+1)*65 clocks after rst; a CPU sync of an axis whose reset sync has not run
//   yet gives that sync its value).  The slot memory and the governor enable / ksh copies are not
//   reset (their configuration contents, kept over rst).
// Resources (Yosys xc6s, N = 4, out of context): NAXES = 1 212 LUT (17 SRLC32E) / 247 FF /
//   1 RAMB16; NAXES = 4 323 LUT (51 of them SRLC32E / RAM32M) / 154 FF / 1.5 RAMB16; no DSP
//   (406 LUT / 1 RAMB16 at NAXES = 4 with the state in SRLs; 198 at NAXES = 1, mapping noise).
//   With the braking distance (V, B, passes G1 / G4 / G5): NAXES = 4 362 LUT / 164 FF / 1.5 RAMB16;
//   one-axis top +24 LUT / +10 FF (3568 / 5146).
`default_nettype none
`include "empc_formats.vh"
module ref_gen #(
    parameter integer N = `EMPC_N,
    parameter integer NAXES = 1,
    parameter integer AW = (N < 2) ? 1 : $clog2(N + 1),
    parameter integer AXB = (NAXES < 2) ? 0 : $clog2(NAXES)      // axis bits (derived, 0 at NAXES = 1)
) (
    input  wire                clk,
    input  wire                rst,
    input  wire                seg_we,
    input  wire                seg_re,
    input  wire [AXB+3:0]      seg_slot,                   // {axis, slot}
    input  wire [2:0]          seg_field,
    input  wire [31:0]         seg_wdata,
    output reg  [31:0]         seg_rdata,
    input  wire [NAXES-1:0]    start,
    input  wire [4*NAXES-1:0]  start_slot,                 // axis a: [4a+3:4a]
    input  wire [NAXES-1:0]    sync,
    output wire [5:0]          sync_idx,
    input  wire [NAXES-1:0]    sync_bit,
    input  wire [NAXES-1:0]    advance,
    input  wire [AXB+AW-1:0]   rd_age,                     // {axis, age}
    input  wire [5:0]          rd_bit,
    output wire                rd_q,
    output wire [NAXES-1:0]    w_ok,
    output wire [NAXES-1:0]    busy,
    input  wire [NAXES-1:0]    hold,
    input  wire [NAXES-1:0]    task_pos,
    output reg  [NAXES-1:0]    gov_ev
);
    localparam [2:0] F_LEN = 3'd0, F_R0 = 3'd1, F_D1 = 3'd3, F_D2 = 3'd5, F_FLAGS = 3'd6;
    // internal axis numbers are AXW bits wide (1 at NAXES = 1: then always 0); per-axis vectors
    // are padded to NAP = 2^AXW entries (the padding is constant 0 and synthesises away)
    localparam integer AXW = (AXB < 1) ? 1 : AXB;
    localparam integer NAP = 1 << AXW;
    localparam integer MW = AXB + 12;                      // slot memory address {axis, slot, field, bit}

    // ---------------- slot memory: block RAM, port A x32 (CPU), port B x1 (engine) ----------------
    reg  mem [0:(1 << MW) - 1];
    integer mi, ai, ii;
    localparam [31:0] GOV_VMAX_LO = `EMPC_GOV_VMAX_LO, GOV_VMAX_HI = `EMPC_GOV_VMAX_HI,
                      GOV_A_LO = `EMPC_GOV_A_LO, GOV_A_HI = `EMPC_GOV_A_HI;
    localparam [4:0]  GOV_KSH = `EMPC_GOV_KSH;
    localparam        GOV_EN = (`EMPC_GOV_EN != 0);
    localparam [31:0] GOV_CFG = {19'd0, GOV_KSH, 7'd0, GOV_EN};
    initial begin
        for (mi = 0; mi < (1 << MW); mi = mi + 1) mem[mi] = 1'b0;
        for (ii = 0; ii < (1 << AXB); ii = ii + 1)
            for (mi = 0; mi < 32; mi = mi + 1) begin       // field 7 of slots 0..4 of every axis: governor words
                mem[ii * 4096 + 0 * 256 + 7 * 32 + mi] = GOV_VMAX_LO[mi];
                mem[ii * 4096 + 1 * 256 + 7 * 32 + mi] = GOV_VMAX_HI[mi];
                mem[ii * 4096 + 2 * 256 + 7 * 32 + mi] = GOV_A_LO[mi];
                mem[ii * 4096 + 3 * 256 + 7 * 32 + mi] = GOV_A_HI[mi];
                mem[ii * 4096 + 4 * 256 + 7 * 32 + mi] = GOV_CFG[mi];
            end
    end
    wire is_flags = (seg_field == F_FLAGS);
    always @(posedge clk) begin
        if (seg_we)
            for (mi = 0; mi < 32; mi = mi + 1)
                if (mi < 8 || !is_flags)               // flags: byte 0 only, bits 7:2 written 0
                    mem[{seg_slot, seg_field, mi[4:0]}] <= (mi >= 2 && is_flags) ? 1'b0 : seg_wdata[mi];
        if (!seg_re)
            seg_rdata <= 32'd0;
        else
            for (mi = 0; mi < 32; mi = mi + 1) seg_rdata[mi] <= mem[{seg_slot, seg_field, mi[4:0]}];
    end
    reg  [MW-1:0] rb_addr;                             // port B: {axis, slot, field, bit}
    reg           rb_q;
    always @(posedge clk) rb_q <= mem[rb_addr];

    // ---------------- engine registers (shared: the operation that runs) ----------------
    localparam [3:0] K_FLG = 4'd0, K_HEAD = 4'd1, K_D1 = 4'd2, K_D2 = 4'd3, K_LEN = 4'd4, K_SYNC = 4'd5,
                     K_G1 = 4'd6, K_G2 = 4'd7, K_G3 = 4'd8, K_G4 = 4'd9, K_G5 = 4'd10;
    reg         run;                                   // a pass is running
    reg  [AXW-1:0] ax_r;                               // axis of the running operation
    wire [AXW-1:0] ax = (NAXES > 1) ? ax_r : {AXW{1'b0}};
    reg  [3:0]  kind;
    reg         act;                                   // past the lead clock
    reg  [5:0]  t;                                     // bit issued (address) in this clock
    reg  [5:0]  jc;                                    // bit consumed in this clock (act = 1)
    reg  [AW-1:0] cp;                                  // sync: copies still to run
    reg         m_load, m_hold, m_rel, rst_sync;
    reg  [3:0]  ld_slot;
    reg         last_nx, one_acc;
    reg         ch, cd, br, d2s;
    reg         g_on, gv_hold, gv_pos;
    reg  [4:0]  ksh;                                   // latched when an advance begins
    reg         k0, k1, k2;                            // governor: carries of a pass's adders
    reg         e_sgn, ovr, x_sgn;                     // sign of e, sb tap past bit 63, sign of x1 / vdc
    reg         hi1, lo1, hi2, lo2, s2, v_nz, v_sgn, dv_nz;
    reg         g_nz, g_sgn, hblk;                     // speed hold: g != 0, sign of g; vd = 0 in G2 (or brake)
    reg         x1z, slow, up, dn, vp;                 // braking: x1 = 0, no speed-up, V up / down, V bit j-1
    reg         k7;                                    // braking: carry of B + ~V in G1 (out: B > V, i.e. n >= 2)
    reg         k3, k4, k5, k6;                        // braking: carries (G1: |e|, |e| - B, B + 2V, |e| - (B + 2V);
                                                       // G4: |v'|, |v'| - V - 1, |v'| + a, |v'| + a - V - 1; G5: V', B')

    // ---------------- per-axis pending flags (flip-flops) ----------------
    reg  [NAP-1:0] adv_pend, sync_pend, pend;
    reg  [NAP-1:0] rz;                                 // the pending sync is the reset's (value 0)
    reg  [3:0]     pend_slot [0:NAP-1];
    wire [AXW-1:0] nx;                                 // the axis the next operation serves (chosen below)

    // ---------------- per-axis segment state (LUT-RAM {axis} at NAXES > 1, flip-flops at 1) ----------------
    // written by the engine at its axis (ax), read there and at the next axis (nx) when an operation
    // begins: ends (the active segment ends, len != 0), rem_one (remaining == 1), last (the active
    // segment is the last), slot (the active slot); the governor's enable / ksh, a copy of field 7
    // of slot 4 of each axis (written with it by the CPU, initialised with it at configuration,
    // kept over rst like the slot memory)
    reg            ends_we, ends_wd, rem_one_we, rem_one_wd, last_we, last_wd, slot_we, gcfg_we;
    /* verilator lint_off UNUSEDSIGNAL */
    wire           zclr;                               // NAXES = 1: parallel clear of d1, d2, remaining, ends (unused at NAXES > 1)
    wire           lclr;                               // NAXES = 1: clear of last (unused at NAXES > 1)
    /* verilator lint_on UNUSEDSIGNAL */
    wire           ends_ax, ends_nx, rem_one_nx, last_nx_r;
    wire [3:0]     slot_nx;
    wire           gen_nx;
    wire [4:0]     gksh_nx;
    // ---------------- axis fields of the ports ----------------
    wire [AXW-1:0] rd_ax;
    wire [AXB+3:0] ld_slot_x, g_slot_x;
    wire [3:0]     g_slot;
    generate
        if (NAXES > 1) begin : g_ax
            assign rd_ax = rd_age[AXB+AW-1:AW];
            assign ld_slot_x = {ax, ld_slot};
            assign g_slot_x = {ax, g_slot};
        end else begin : g_ax1
            assign rd_ax = 1'b0;
            assign ld_slot_x = ld_slot;
            assign g_slot_x = g_slot;
        end
    endgenerate
    wire [AW-1:0] rd_age_w = rd_age[AW-1:0];
    always @(*) gcfg_we = seg_we && seg_field == 3'd7 && seg_slot[3:0] == 4'd4;
    generate
        if (NAXES > 1) begin : g_st
            reg            ends_m    [0:NAP-1];
            reg            rem_one_m [0:NAP-1];
            reg            last_m    [0:NAP-1];
            reg  [3:0]     slot_m    [0:NAP-1];
            reg            gen_m     [0:NAP-1];
            reg  [4:0]     gksh_m    [0:NAP-1];
            wire [AXW-1:0] seg_ax = seg_slot[AXB+3:4];
            integer        si;
            initial begin
                for (si = 0; si < NAP; si = si + 1) begin
                    ends_m[si] = 1'b0;
                    rem_one_m[si] = 1'b0;
                    last_m[si] = 1'b0;
                    slot_m[si] = 4'd0;
                    gen_m[si] = GOV_EN;
                    gksh_m[si] = GOV_KSH;
                end
            end
            always @(posedge clk) begin
                if (ends_we) ends_m[ax] <= ends_wd;
                if (rem_one_we) rem_one_m[ax] <= rem_one_wd;
                if (last_we) last_m[ax] <= last_wd;
                if (slot_we) slot_m[ax] <= ld_slot;
                if (gcfg_we) begin
                    gen_m[seg_ax] <= seg_wdata[0];
                    gksh_m[seg_ax] <= seg_wdata[12:8];
                end
            end
            assign ends_ax = ends_m[ax];
            assign ends_nx = ends_m[nx];
            assign rem_one_nx = rem_one_m[nx];
            assign last_nx_r = last_m[nx];
            assign slot_nx = slot_m[nx];
            assign gen_nx = gen_m[nx];
            assign gksh_nx = gksh_m[nx];
        end else begin : g_st1
            reg            ends_r, rem_one_r, last_r, gen_r;
            reg  [3:0]     slot_r;
            reg  [4:0]     gksh_r;
            initial begin
                ends_r = 1'b0;
                rem_one_r = 1'b0;
                last_r = 1'b0;
                slot_r = 4'd0;
                gen_r = GOV_EN;
                gksh_r = GOV_KSH;
            end
            always @(posedge clk) begin
                if (zclr) ends_r <= 1'b0;
                else if (ends_we) ends_r <= ends_wd;
                if (rem_one_we) rem_one_r <= rem_one_wd;
                if (lclr) last_r <= 1'b0;
                else if (last_we) last_r <= last_wd;
                if (slot_we) slot_r <= ld_slot;
                if (gcfg_we) begin
                    gen_r <= seg_wdata[0];
                    gksh_r <= seg_wdata[12:8];
                end
            end
            assign ends_ax = ends_r;
            assign ends_nx = ends_r;
            assign rem_one_nx = rem_one_r;
            assign last_nx_r = last_r;
            assign slot_nx = slot_r;
            assign gen_nx = gen_r;
            assign gksh_nx = gksh_r;
        end
    endgenerate

    // ---------------- per-axis delay line (SRL, the axis's own clock enable) ----------------
    // delay line w_k .. w_{k+N} ((N+1)*64, SRL LUT-RAM): each pass shifts in a new head word; the
    // old head is read at a fixed tap (bit 63).
    localparam integer DL = (N + 1) * 64;
    reg  [NAXES*DL-1:0] dl;
    reg                 dl_sh, dl_in, d1_sh, d1_in, d2_sh, d2_in, rem_sh, rem_in, rt_sh, rt_in, v_sh, v_in;
    reg                 vq_sh, vq_in, bq_sh, bq_in;
    wire [NAP-1:0]      ax_hot;
    always @(posedge clk)
        for (ai = 0; ai < NAXES; ai = ai + 1)
            if (ax_hot[ai] && dl_sh) dl[ai * DL +: DL] <= {dl[ai * DL +: DL - 1], dl_in};
    // ---------------- d1 (64), d2 (32), remaining (32), the governor's rt and v (64) ----------------
    // Bit-serial words, LSB first: every pass that changes one of them visits its bits j = 0 .. L-1
    // in the clocks jc = j of the pass (L = 64 or 32), reading bit j and writing the new bit j in the
    // same clock.  st_* = bit jc of the engine's axis's word (for d2 / remaining only meaningful for
    // jc < 32).  d1, d2 (and remaining) are cleared when a sync begins and by a hold: at NAXES > 1 by
    // writing zeros (the first sync pass, the hold's head pass), at NAXES = 1 by a parallel clear
    // (zclr, also at rst).
    localparam          SHZ = (NAXES > 1);
    // NAXES > 1: also the engine's copy of the head w_{k+N} (st_w, the tap: bit jc of the old head
    // while the delay line shifts, of the head in a governed head pass, where it stands still).
    wire                st_d1, st_d2, st_rem, st_rt, st_v, st_w, st_vq, st_bq;
    generate
        if (NAXES > 1) begin : g_sram
            // block RAM {axis, bit} x {B, V, w, v, rt, remaining, d2, d1}: read bit t (the next bit) one clock
            // ahead like the slot memory, write bit jc in every clock of a pass (a word that does not
            // change writes back the bit it read: no read and write of the same address in one clock).
            // In a pass that does not change a word its bit is not needed (the carries that see it are
            // preset at every lead clock).
            (* ram_style = "block" *) reg [7:0] st_m [0:NAP*64-1];
            reg  [7:0]  st_q;
            integer     sj;
            initial for (sj = 0; sj < NAP * 64; sj = sj + 1) st_m[sj] = 8'd0;
            always @(posedge clk) begin
                st_q <= st_m[{ax, t}];
                if (run && act)
                    st_m[{ax, jc}] <= {bq_sh ? bq_in : st_q[7], vq_sh ? vq_in : st_q[6],
                                       dl_sh ? dl_in : st_q[5], v_sh ? v_in : st_q[4], rt_sh ? rt_in : st_q[3],
                                       rem_sh ? rem_in : st_q[2], d2_sh ? d2_in : st_q[1], d1_sh ? d1_in : st_q[0]};
            end
            assign {st_bq, st_vq, st_w, st_v, st_rt, st_rem, st_d2, st_d1} = st_q;
        end else begin : g_sff
            // one axis: shift registers (rt, v, V, B: SRL; d1, d2, remaining: flip-flops with a parallel clear)
            reg  [63:0] d1, rt, v, vq, bq;
            reg  [31:0] d2, rem;
            always @(posedge clk)
                if (ax_hot[0]) begin
                    if (rt_sh) rt <= {rt[62:0], rt_in};
                    if (v_sh)  v  <= {v[62:0], v_in};
                    if (vq_sh) vq <= {vq[62:0], vq_in};
                    if (bq_sh) bq <= {bq[62:0], bq_in};
                end
            always @(posedge clk)
                if (zclr) begin
                    d1  <= 64'd0;
                    d2  <= 32'd0;
                    rem <= 32'd0;
                end else if (ax_hot[0]) begin
                    if (d1_sh)  d1  <= {d1_in, d1[63:1]};
                    if (d2_sh)  d2  <= {d2_in, d2[31:1]};
                    if (rem_sh) rem <= {rem_in, rem[31:1]};
                end
            assign st_d1 = d1[0];
            assign st_d2 = d2[0];
            assign st_rem = rem[0];
            assign st_rt = rt[63];
            assign st_v = v[63];
            assign st_vq = vq[63];
            assign st_bq = bq[63];
            assign st_w = 1'b0;                            // the tap is the delay line's read port
        end
    endgenerate

    // one dynamic read port per axis's delay line: bit 63 (the old head bit j in clock j of a pass)
    // while it shifts, bit j of the head (63 - j) in a governed head pass (the line stands still),
    // else bit 63 - rd_bit of word rd_age (64 * age + 63 - bit) for the readout
    wire          dl_busy, g_head;
    wire [5:0]    jcw;
    wire [NAP-1:0] dl_q;
    wire [NAP-1:0] in_adv, in_sync, in_start, in_sbit, in_hold, in_pos;
    wire [3:0]     in_sslot [0:NAP-1];
    genvar ga;
    generate
        for (ga = 0; ga < NAP; ga = ga + 1) begin : g_axis
            localparam [AXW-1:0] AI = ga;
            assign ax_hot[ga] = (ax == AI);
            if (ga < NAXES) begin : g_on_ax
                wire [DL-1:0]   dla = dl[ga * DL +: DL];
                // NAXES = 1: one read port, as the engine and the readout never need it in the same
                // clock; NAXES > 1: the readout (any axis, while the engine runs another) only, the engine's
                // tap is a copy of word 0 (w_{k+N}) in the state RAM (st_w)
                wire [AW+5:0]   idx = (NAXES == 1 && dl_busy && ax_hot[ga]) ? {{AW{1'b0}}, 6'd63} :
                                      (NAXES == 1 && g_head && ax_hot[ga]) ? {{AW{1'b0}}, ~jcw} : {rd_age_w, ~rd_bit};
                assign dl_q[ga] = dla[idx];
                assign in_adv[ga] = advance[ga];
                assign in_sync[ga] = sync[ga];
                assign in_start[ga] = start[ga];
                assign in_sbit[ga] = sync_bit[ga];
                assign in_hold[ga] = hold[ga];
                assign in_pos[ga] = task_pos[ga];
                assign in_sslot[ga] = start_slot[4 * ga +: 4];
            end else begin : g_pad
                assign dl_q[ga] = 1'b0;
                assign in_adv[ga] = 1'b0;
                assign in_sync[ga] = 1'b0;
                assign in_start[ga] = 1'b0;
                assign in_sbit[ga] = 1'b0;
                assign in_hold[ga] = 1'b0;
                assign in_pos[ga] = 1'b0;
                assign in_sslot[ga] = 4'd0;
            end
        end
    endgenerate
    wire          tap = (NAXES > 1) ? st_w : dl_q[ax];
    assign rd_q = dl_q[rd_ax];

    // ---------------- governor scratch words (shared SRLs): sa, sb ----------------
    reg  [63:0]   sa, sb;
    reg           sa_sh, sb_sh;
    reg           sa_in, sb_in;
    always @(posedge clk) begin
        if (sa_sh) sa <= {sa[62:0], sa_in};
        if (sb_sh) sb <= {sb[62:0], sb_in};
    end
    wire          rt_o = st_rt, v_o = st_v, sa_o = sa[63];
    wire          sb_t = sb[{1'b1, ~ksh}];             // bit j + ksh of sb in clock j (63 - ksh)

    // ---------------- engine ----------------
    assign jcw = jc;
    wire        ends = ends_ax;
    wire        gk   = (kind == K_G1) || (kind == K_G2) || (kind == K_G3) || (kind == K_G4);
    wire        gk5  = gk || (kind == K_G5);                 // the passes that read field 7
    wire [5:0]  jlast = (kind == K_FLG) ? 6'd1 : (kind == K_D2 || kind == K_LEN) ? 6'd31 : 6'd63;
    wire        last_bit = act && (jc == jlast);
    // field of the bit issued in this clock
    wire [2:0]  fld = (kind == K_FLG) ? F_FLAGS : (kind == K_HEAD) ? (F_R0 + {2'b00, t[5]}) :
                      (kind == K_D1) ? (F_D1 + {2'b00, t[5]}) : (kind == K_D2) ? F_D2 :
                      gk5 ? 3'd7 : F_LEN;
    // governor words: vmax in slots 0/1 (G1, G2), a in slots 2/3 (G3, G4, G5); bit 63 reads as 0
    assign      g_slot = {2'b00, (kind == K_G3) || (kind == K_G4) || (kind == K_G5), t[5]};
    wire        pm = rb_q && (jc != 6'd63);            // vmax / a bit jc

    // head pass arithmetic (bit jc)
    wire        d1b  = st_d1;
    wire        d2x  = (jc[5] ? d2s : st_d2);
    wire        h1   = rt_o ^ d1b ^ ch;
    wire        d1n  = d1b ^ d2x ^ cd;
    wire        remn = st_rem ^ br;
    assign      sync_idx = jc;
    wire        sync_in  = !rst_sync && in_sbit[ax];
    wire        in_head = (kind == K_SYNC) ? ((cp == N[AW-1:0]) ? sync_in : tap) :
                          (m_load && !m_rel) ? rb_q : h1;
    wire        normal  = !m_load && !m_hold;
    assign      g_head  = run && (kind == K_HEAD) && g_on;
    wire        first_sync = run && act && (kind == K_SYNC) && (cp == N[AW-1:0]);
    wire        head_sh = run && act && (kind == K_HEAD) && !jc[5] && (normal || (SHZ && m_hold));

    // governor pass arithmetic (bit jc); k0..k2 are the carries of the pass's adders
    //   head: x1 = r_new - r_old -> sa (k0), e = r_old - g -> sb (k1)
    wire        x1b  = in_head ^ ~rt_o ^ k0;
    wire        eb   = rt_o ^ ~tap ^ k1;
    //   G1: vd = x1 + (e >>> ksh) -> sa (k0); vd + ~vmax (k1), vd + vmax (k2): the clamps
    wire        esb  = ovr ? e_sgn : sb_t;
    wire        vdb  = sa_o ^ esb ^ k0;
    //   G2: vdc = clamp(vd) (-vmax = ~vmax + 1: k1), dv = vdc + ~v + 1 -> sb (k0)
    wire        nvm  = ~pm ^ k1;
    wire        vdc  = hblk ? 1'b0 : hi1 ? pm : lo1 ? nvm : sa_o;
    wire        dvb  = vdc ^ ~v_o ^ k0;
    //   G3: dv + ~a (k1), dv + a (k2): the clamps; dv recirculates in sb
    //   G4: dvc = clamp(dv) (-a: k1) or 0 (hold), v' = v + dvc (k0), g' = g + v' (k2) -> delay line
    wire        na   = ~pm ^ k1;
    wire        blk  = (gv_hold || slow) && gv_pos && dv_nz && v_nz && (s2 == v_sgn);
    wire        dvc  = blk ? 1'b0 : hi2 ? pm : lo2 ? na : sb[63];
    wire        vnb  = v_o ^ dvc ^ k0;
    wire        gnb  = tap ^ vnb ^ k2;
    // braking distance (position task): V = n a >= |v|, B = a n (n + 1) / 2, per axis (rtlmodel/ref_gen.py)
    //   G1: |e| (k3), |e| - B (k4), T = B + 2V (k5, vp = V bit j-1), |e| - T (k6): brake / no speed-up
    wire        eo   = sb[63];                         // e, bit jc (sb recirculates in G1)
    wire        aex  = eo ^ e_sgn;
    wire        aeb  = aex ^ k3;
    wire        d0b  = aeb ^ ~st_bq ^ k4;
    wire        t1b  = st_bq ^ vp ^ k5;
    wire        dtb = aeb ^ ~t1b ^ k6;
    wire        zc   = gv_pos && x1z && (v_nz || v_o) && (v_o == e_sgn);  // at bit 63 (v streams in G1)
    //   G4: w = |v'| by the sign of v (of dv when v = 0) (k3), w - V - 1 (k4), w + a (k5), w + a - V - 1 (k6)
    wire        sw   = v_nz ? v_sgn : s2;
    wire        wx   = vnb ^ sw;
    wire        wb   = wx ^ k3;
    wire        ub   = wb ^ ~st_vq ^ k4;
    wire        tb   = wb ^ pm ^ k5;
    wire        qb   = tb ^ ~st_vq ^ k6;
    //   G5: V' = V + a (up) / V - a (down) (k3), B' = B + V' (up) / B - V (down) (k4)
    wire        dnx  = dn && !up;
    wire        as5  = up ? pm : (dnx && !pm);
    wire        vqn  = st_vq ^ as5 ^ k3;
    wire        bs5  = up ? vqn : (dnx && !st_vq);
    wire        bqn  = st_bq ^ bs5 ^ k4;
    wire        k3n  = (kind == K_G1) ? (aex & k3) : (kind == K_G4) ? (wx & k3) :
                       ((st_vq & as5) | (k3 & (st_vq ^ as5)));
    wire        k4n  = (kind == K_G1) ? ((aeb & ~st_bq) | (k4 & (aeb ^ ~st_bq))) :
                       (kind == K_G4) ? ((wb & ~st_vq) | (k4 & (wb ^ ~st_vq))) :
                       ((st_bq & bs5) | (k4 & (st_bq ^ bs5)));
    wire        k5n  = (kind == K_G1) ? ((st_bq & vp) | (k5 & (st_bq ^ vp))) : ((wb & pm) | (k5 & (wb ^ pm)));
    wire        k6n  = (kind == K_G1) ? ((aeb & ~t1b) | (k6 & (aeb ^ ~t1b))) : ((tb & ~st_vq) | (k6 & (tb ^ ~st_vq)));
    //   G1: B + ~V (k7): its carry out is B > V, n >= 2; below (|v| <= a) the proportional catch-up stops
    //   in time by itself, and a brake there would stop the last approach every other period
    wire        k7n  = (st_bq & ~st_vq) | (k7 & (st_bq ^ ~st_vq));

    // compare operand of G1 (vd) / G3 (dv) and its carries
    wire        cx   = (kind == K_G1) ? vdb : sb[63];
    wire        k1n  = (kind == K_G2 || kind == K_G4) ? (~pm & k1) :
                       (kind == K_HEAD) ? ((rt_o & ~tap) | (k1 & (rt_o ^ ~tap))) :
                       ((cx & ~pm) | (k1 & (cx ^ ~pm)));          // G1, G3: cx + ~m
    wire        k2n  = (kind == K_G4) ? ((tap & vnb) | (k2 & (tap ^ vnb))) :
                       ((cx & pm) | (k2 & (cx ^ pm)));            // G1, G3: cx + m
    wire        k0n  = (kind == K_HEAD) ? ((in_head & ~rt_o) | (k0 & (in_head ^ ~rt_o))) :
                       (kind == K_G1) ? ((sa_o & esb) | (k0 & (sa_o ^ esb))) :
                       (kind == K_G2) ? ((vdc & ~v_o) | (k0 & (vdc ^ ~v_o))) :
                       ((v_o & dvc) | (k0 & (v_o ^ dvc)));        // G4
    // 65-bit signs at bit 63: sum / difference overflow (G1: x1 + es; G2: vdc - v)
    wire        ov1  = (sa_o == esb) && (vdb != sa_o);
    wire        ov2  = (vdc != v_o) && (dvb != vdc);
    // clamp decisions at bit 63 (operand sign sx, carries out of bit 63):
    //   above m: sx ^ carry(x + ~m) = 1;  below -m: sx ^ carry(x + m) = 1 (m >= 0, bit 63 = 0)
    wire        c_hi = (cx & ~pm) | (k1 & (cx ^ ~pm));
    wire        c_lo = (cx & pm) | (k2 & (cx ^ pm));

    wire        dl_pass = run && act && (kind == K_SYNC || (kind == K_HEAD && !g_on) || kind == K_G4);

    always @(*) begin
        dl_sh = dl_pass;
        dl_in = (kind == K_G4) ? gnb : in_head;
        rb_addr = gk5 ? {g_slot_x, fld, t[4:0]} : {ld_slot_x, fld, t[4:0]};
        // rt: the new target in the head pass, the sync value in the first sync pass
        rt_sh = run && act && (kind == K_HEAD || (kind == K_SYNC && cp == N[AW-1:0]));
        rt_in = in_head;
        // v: 0 in a head pass without the governor and in the first sync pass, v' in G4,
        // recirculates in G2
        v_sh  = run && act && ((kind == K_HEAD && !g_on) || first_sync || kind == K_G1 || kind == K_G2 ||
                               kind == K_G4);
        v_in  = (kind == K_G4) ? vnb : (kind == K_G1 || kind == K_G2) ? v_o : 1'b0;
        // V, B: 0 where v is cleared, read in G1 and G4 (recirculate), updated in G5
        vq_sh = run && act && ((kind == K_HEAD && !g_on) || first_sync || kind == K_G1 || kind == K_G4 ||
                               kind == K_G5);
        vq_in = (kind == K_G5) ? vqn : (kind == K_G1 || kind == K_G4) ? st_vq : 1'b0;
        bq_sh = vq_sh;
        bq_in = (kind == K_G5) ? bqn : (kind == K_G1 || kind == K_G4) ? st_bq : 1'b0;
        sa_sh = run && act && ((kind == K_HEAD && g_on) || kind == K_G1 || kind == K_G2);
        sa_in = (kind == K_G1) ? vdb : (kind == K_G2) ? sa_o : x1b;
        sb_sh = run && act && ((kind == K_HEAD && g_on) || gk);
        sb_in = (kind == K_HEAD) ? eb : (kind == K_G2) ? dvb : sb[63];
        // d1: d1' (0 in a hold) in the head pass, loaded in D1, cleared (0 shifted in) by the
        // first sync pass; d2 (recirculates in a normal head pass) and remaining: bits 0..31 of
        // the head pass (0 in a hold), loaded in D2 / LEN, cleared by the first sync pass
        d1_sh = run && act && (kind == K_HEAD || kind == K_D1 || (SHZ && first_sync));
        d1_in = (kind == K_D1) ? rb_q : ((!SHZ || kind == K_HEAD) && normal) ? d1n : 1'b0;
        d2_sh = head_sh || (run && act && kind == K_D2) || (SHZ && first_sync && !jc[5]);
        d2_in = (kind == K_D2) ? rb_q : ((!SHZ || kind == K_HEAD) && normal) ? st_d2 : 1'b0;
        // (remaining needs no clear: it counts only while ends = 1, and a sync and a hold clear ends)
        rem_sh = (head_sh && normal) || (run && act && kind == K_LEN);
        rem_in = (kind == K_LEN) ? rb_q : remn;
    end

    // per-axis segment state writes (at ax; never in a reset clock)
    wire        sync_lead = run && !act && (kind == K_SYNC) && (cp == N[AW-1:0]);
    always @(*) begin
        // ends: len != 0, bit by bit in LEN; cleared when a sync begins and by a hold
        ends_we = (run && act && kind == K_LEN && (jc == 6'd0 || rb_q)) ||
                  (SHZ && (sync_lead || (last_bit && kind == K_HEAD && m_hold)));
        ends_wd = (kind == K_LEN) && rb_q;
        // remaining == 1: after a head pass without a load, and len == 1 after LEN (bit 31 is this clock's)
        rem_one_we = last_bit && ((kind == K_HEAD && !m_load) || kind == K_LEN);
        rem_one_wd = (kind == K_LEN) ? (one_acc && !rb_q) : (normal && ends && one_acc);
        // last: the loaded flag after LEN, cleared when a sync begins; slot: the loaded slot
        last_we = (last_bit && kind == K_LEN) || (SHZ && sync_lead);
        last_wd = (kind == K_LEN) && last_nx;
        slot_we = last_bit && kind == K_LEN;
    end

    assign dl_busy = run && (kind == K_SYNC || (kind == K_HEAD && !g_on) || kind == K_G4);
    wire   w_run = run && (kind == K_FLG || kind == K_HEAD || kind == K_SYNC || gk);
    generate
        for (ga = 0; ga < NAXES; ga = ga + 1) begin : g_out
            assign busy[ga] = (run && ax_hot[ga]) || adv_pend[ga] || sync_pend[ga];
            assign w_ok[ga] = !adv_pend[ga] && !sync_pend[ga] && !(w_run && ax_hot[ga]);
        end
    endgenerate

    // operation start (engine idle): a pending sync first (lowest axis first), else a pending
    // advance (lowest axis first)
    reg  [AXW-1:0] nx_s, nx_a;
    always @(*) begin
        nx_s = {AXW{1'b0}};
        nx_a = {AXW{1'b0}};
        for (ai = NAP - 1; ai >= 0; ai = ai - 1) begin
            if (sync_pend[ai]) nx_s = ai[AXW-1:0];
            if (adv_pend[ai]) nx_a = ai[AXW-1:0];
        end
    end
    wire        any_sync = |sync_pend[NAXES-1:0];
    assign nx = (NAXES < 2) ? {AXW{1'b0}} : any_sync ? nx_s : nx_a;
    wire        go_sync = !run && any_sync;
    wire        go_adv  = !run && !any_sync && (|adv_pend[NAXES-1:0]);
    wire        seg_end = ends_nx && rem_one_nx;
    wire        g_load  = pend[nx] || (seg_end && !last_nx_r);
    wire        g_hold  = !pend[nx] && seg_end && last_nx_r;
    assign      zclr = !SHZ && (rst || go_sync || (m_hold && kind == K_HEAD && last_bit));
    assign      lclr = !SHZ && (rst || go_sync);


    always @(posedge clk) begin
        for (ai = 0; ai < NAXES; ai = ai + 1) gov_ev[ai] <= 1'b0;
        if (rst) begin
            run <= 1'b1;                               // clear axis 0's delay line: sync to 0
            ax_r <= {AXW{1'b0}};
            kind <= K_SYNC;
            act <= 1'b0;
            t <= 6'd0;
            jc <= 6'd0;
            cp <= N[AW-1:0];
            rst_sync <= 1'b1;
            for (ai = 0; ai < NAP; ai = ai + 1) begin
                adv_pend[ai] <= 1'b0;
                sync_pend[ai] <= (ai > 0 && ai < NAXES); // the other axes' reset syncs queue
                rz[ai] <= (ai > 0 && ai < NAXES);
                pend[ai] <= 1'b0;
                pend_slot[ai] <= 4'd0;
            end
            ld_slot <= 4'd0;
            m_load <= 1'b0;
            m_hold <= 1'b0;
            m_rel <= 1'b0;
            last_nx <= 1'b0;
            one_acc <= 1'b0;
            ch <= 1'b0;
            cd <= 1'b0;
            br <= 1'b0;
            d2s <= 1'b0;
            g_on <= 1'b0;
            gv_hold <= 1'b0;
            gv_pos <= 1'b0;
            ksh <= 5'd0;
            k0 <= 1'b0;
            k1 <= 1'b0;
            k2 <= 1'b0;
            e_sgn <= 1'b0;
            ovr <= 1'b0;
            x_sgn <= 1'b0;
            hi1 <= 1'b0;
            lo1 <= 1'b0;
            hi2 <= 1'b0;
            lo2 <= 1'b0;
            s2 <= 1'b0;
            v_nz <= 1'b0;
            v_sgn <= 1'b0;
            dv_nz <= 1'b0;
            g_nz <= 1'b0;
            g_sgn <= 1'b0;
            hblk <= 1'b0;
            x1z <= 1'b0;
            slow <= 1'b0;
            up <= 1'b0;
            dn <= 1'b0;
            vp <= 1'b0;
            k3 <= 1'b0;
            k4 <= 1'b0;
            k5 <= 1'b0;
            k6 <= 1'b0;
            k7 <= 1'b0;
        end else begin
            for (ai = 0; ai < NAP; ai = ai + 1) begin
                if (in_adv[ai]) adv_pend[ai] <= 1'b1;
                if (in_sync[ai]) begin
                    sync_pend[ai] <= 1'b1;
                    rz[ai] <= 1'b0;                    // the CPU's value, not the reset's
                end
                if (in_start[ai]) begin
                    pend[ai] <= 1'b1;
                    pend_slot[ai] <= in_sslot[ai];
                end
            end
            if (!run) begin
                t <= 6'd0;
                act <= 1'b0;
                if (go_sync) begin
                    sync_pend[nx] <= in_sync[nx];      // a sync in this clock runs again after
                    rz[nx] <= 1'b0;
                    run <= 1'b1;
                    ax_r <= nx;
                    kind <= K_SYNC;
                    cp <= N[AW-1:0];
                    rst_sync <= SHZ && rz[nx];
                end else if (go_adv) begin
                    adv_pend[nx] <= in_adv[nx];
                    run <= 1'b1;
                    ax_r <= nx;
                    m_load <= g_load;
                    m_hold <= g_hold;
                    m_rel <= 1'b0;
                    ld_slot <= pend[nx] ? pend_slot[nx] : slot_nx + 4'd1;
                    if (pend[nx] && !in_start[nx]) pend[nx] <= 1'b0;
                    kind <= g_load ? K_FLG : K_HEAD;
                    g_on <= gen_nx;
                    ksh <= gksh_nx;
                    gv_hold <= in_hold[nx];
                    gv_pos <= in_pos[nx];
                end
            end else begin
                // bit counters: t issues, jc = t delayed
                t <= t + 6'd1;
                jc <= t;
                act <= 1'b1;
                if (act) begin
                    case (kind)
                        K_FLG: begin
                            if (jc == 6'd0) m_rel <= rb_q;
                            else last_nx <= rb_q;
                        end
                        K_HEAD: if (normal) begin
                            if (jc == 6'd31) d2s <= st_d2;
                        end
                        K_LEN: begin
                            if (jc == 6'd0) one_acc <= rb_q;
                            else if (rb_q) one_acc <= 1'b0;
                        end
                        default: ;
                    endcase
                    // carries (cleared at the lead clock below)
                    ch <= (rt_o & d1b) | (ch & (rt_o ^ d1b));
                    cd <= (d1b & d2x) | (cd & (d1b ^ d2x));
                    br <= br & !st_rem;
                    k0 <= k0n;
                    k1 <= k1n;
                    k2 <= k2n;
                    k3 <= k3n;
                    k4 <= k4n;
                    k5 <= k5n;
                    k6 <= k6n;
                    k7 <= k7n;
                    vp <= st_vq;
                    if (kind == K_HEAD && x1b) x1z <= 1'b0;
                    if (kind == K_HEAD && normal && !jc[5]) begin
                        if (jc == 6'd0) one_acc <= remn;
                        else if (remn) one_acc <= 1'b0;
                    end
                    // governor bookkeeping
                    if (kind == K_HEAD && jc == 6'd63) e_sgn <= eb;
                    if (kind == K_HEAD) begin                       // the old head g, bit jc
                        g_nz <= g_nz | tap;
                        g_sgn <= tap;
                    end
                    if (kind == K_G1 && jc == {1'b1, ~ksh}) ovr <= 1'b1;
                    if (kind == K_G1) begin
                        if (v_o) v_nz <= 1'b1;
                        if (jc == 6'd63) v_sgn <= v_o;
                    end
                    if (kind == K_G2) begin
                        if (jc == 6'd63) begin
                            s2 <= ov2 ? vdc : dvb;              // sign of the exact vdc - v
                            x_sgn <= ov2;                       // (overflowed: the clamp is certain)
                        end
                    end
                    if (kind == K_G3 && sb[63]) dv_nz <= 1'b1;
                    if (jc == 6'd63) begin
                        if (kind == K_G1) begin                 // exact vd: 65-bit sign if overflowed
                            hi1 <= ov1 ? !sa_o : (vdb ^ c_hi);
                            lo1 <= ov1 ? sa_o : (vdb ^ c_lo);
                            // speed hold: vd = 0 unless it lowers |g| (g != 0, sign(vd) != sign(g));
                            // position task: vd = 0 (brake) when |e| < B and B > V, no speed-up when |e| < B + 2V
                            hblk <= (gv_hold && !gv_pos && !(g_nz && ((ov1 ? sa_o : vdb) != g_sgn))) ||
                                    (zc && d0b && k7n);
                            slow <= zc && dtb;
                        end
                        if (kind == K_G3) begin
                            hi2 <= x_sgn ? !s2 : (sb[63] ^ c_hi);
                            lo2 <= x_sgn ? s2 : (sb[63] ^ c_lo);
                        end
                        if (kind == K_G4) begin                 // |v'| > V, |v'| + a <= V
                            up <= !ub;
                            dn <= qb;
                        end
                    end
                end else begin
                    ch <= 1'b0;
                    cd <= 1'b0;
                    br <= ends;
                    // carry presets: subtractions and negations start at 1
                    k0 <= (kind == K_HEAD) || (kind == K_G2);
                    k1 <= (kind == K_HEAD) || (kind == K_G2) || (kind == K_G4);
                    k2 <= 1'b0;
                    if (kind == K_G1) ovr <= 1'b0;
                    if (kind == K_G1) v_nz <= 1'b0;
                    k3 <= (kind == K_G1) ? e_sgn : (kind == K_G4) ? sw : (kind == K_G5) && dnx;
                    k4 <= (kind == K_G1) || ((kind == K_G5) && dnx);
                    k5 <= 1'b0;
                    k6 <= (kind == K_G1);
                    k7 <= 1'b0;
                    vp <= 1'b0;
                    if (kind == K_HEAD) x1z <= 1'b1;
                    if (kind == K_G3) dv_nz <= 1'b0;
                    if (kind == K_HEAD) g_nz <= 1'b0;
                end
                if (last_bit) begin
                    t <= 6'd0;
                    act <= 1'b0;
                    case (kind)
                        K_FLG: kind <= K_HEAD;
                        K_HEAD: begin
                            if (g_on) kind <= K_G1;
                            else if (m_load) kind <= K_D1;
                            else run <= 1'b0;
                        end
                        K_G1: kind <= K_G2;
                        K_G2: kind <= K_G3;
                        K_G3: kind <= K_G4;
                        K_G4: begin
                            for (ai = 0; ai < NAXES; ai = ai + 1)
                                if (ax_hot[ai]) gov_ev[ai] <= gv_hold || hi1 || lo1 || hi2 || lo2;
                            kind <= K_G5;
                        end
                        K_G5: begin
                            if (m_load) kind <= K_D1;
                            else run <= 1'b0;
                        end
                        K_D1: kind <= K_D2;
                        K_D2: kind <= K_LEN;
                        K_LEN: begin
                            run <= 1'b0;
                        end
                        default: begin                 // K_SYNC
                            if (cp == {AW{1'b0}}) run <= 1'b0;
                            else cp <= cp - {{(AW-1){1'b0}}, 1'b1};
                        end
                    endcase
                end
            end
        end
    end

`ifndef SYNTHESIS
    initial begin
        if (N < 1) $display("ERROR: ref_gen N=%0d must be >= 1", N);
        if (NAXES < 1 || NAXES > 4) $display("ERROR: ref_gen NAXES=%0d must be 1..4", NAXES);
    end
`endif
endmodule
`default_nettype wire
