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
//   governor enabled:  the head pass writes rt, and passes G1..G4 (64 each) follow it (before
//                      d1 / d2 / len of a load); G4 shifts the delay line
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
//   G1: vd = (r_new - r_old) + ((r_old - g) >>> ksh), compared with +-vmax
//   G2: dv = clamp(vd, +-vmax) [0 in the speed task when hold] - v
//   G3: dv compared with +-a
//   G4: v = v + clamp(dv, +-a) [0 in the position task when hold and dv would raise |v|],
//       g = g + v shifted into the delay line
// vmax, a: field 7 of slots 0/1 and 2/3 (63 bit: bit 63 reads as 0), ksh: field 7 of slot 4,
// bits 12:8.  hold and task_pos are taken when an advance begins; gov_ev pulses at the end
// of G4 when a clamp or the hold changed the reference.  Disabled: g = r, v = 0.
//
// Ports:
//   clk, rst                  clock, synchronous active-high reset
//   seg_we, seg_re, seg_slot[3:0], seg_field[2:0], seg_wdata[31:0]
//                             CPU field write / read of the slot memory
//   seg_rdata[31:0]           field read, valid the clock after seg_re (0 in other clocks);
//                             flags read back as written in bits 1:0, the rest 0
//   start, start_slot[3:0]    begin the profile at start_slot at the next advance
//   sync                      set all outputs to the sync value, zero differences, hold
//   sync_idx[5:0], sync_bit   the sync value, bit by bit: sync_bit = bit sync_idx of the value
//                             (combinational; the value must stay constant until busy falls)
//   advance                   pulse once per control period
//   rd_age, rd_bit[5:0], rd_q reference readout (rd_age 0 = w_{k+N} .. N = w_k)
//   w_ok                      the delay line is current: no sync or advance is pending or
//                             shifting (an advance with a load is done with the delay line
//                             after its head pass)
//   busy                      an operation is running or pending
// Parameters:
//   N                         prediction horizon (delay line N+1 deep), >= 1
// Latency: advance strobe -> w_ok: 66 clocks (no load), 69 (load; busy 199); sync ->
//   w_ok (N+1)*65 clocks (+ a running operation).  Consumers (ctrl_seq) wait for w_ok.
// Reset: differences 0, hold, no start/advance pending, slot 0; the delay line (no
//   reset pins) is cleared by a sync to 0 that starts with rst (busy for (N+1)*65 clocks).
//   The slot memory is not reset (0 after configuration, kept over rst).
// Resources (Yosys xc6s, N = 4): 1 RAMB16 (slot memory, ports x32 / x1), delay line
//   in SRLC32E, 192 state flip-flops; no DSP.
`default_nettype none
`include "empc_formats.vh"
module ref_gen #(
    parameter integer N = `EMPC_N,
    parameter integer AW = (N < 2) ? 1 : $clog2(N + 1)
) (
    input  wire                clk,
    input  wire                rst,
    input  wire                seg_we,
    input  wire                seg_re,
    input  wire [3:0]          seg_slot,
    input  wire [2:0]          seg_field,
    input  wire [31:0]         seg_wdata,
    output reg  [31:0]         seg_rdata,
    input  wire                start,
    input  wire [3:0]          start_slot,
    input  wire                sync,
    output wire [5:0]          sync_idx,
    input  wire                sync_bit,
    input  wire                advance,
    input  wire [AW-1:0]       rd_age,
    input  wire [5:0]          rd_bit,
    output wire                rd_q,
    output wire                w_ok,
    output wire                busy,
    input  wire                hold,
    input  wire                task_pos,
    output reg                 gov_ev
);
    localparam [2:0] F_LEN = 3'd0, F_R0 = 3'd1, F_D1 = 3'd3, F_D2 = 3'd5, F_FLAGS = 3'd6;

    // ---------------- slot memory: block RAM, port A x32 (CPU), port B x1 (engine) ----------------
    reg  mem [0:4095];
    integer mi;
    localparam [31:0] GOV_VMAX_LO = `EMPC_GOV_VMAX_LO, GOV_VMAX_HI = `EMPC_GOV_VMAX_HI,
                      GOV_A_LO = `EMPC_GOV_A_LO, GOV_A_HI = `EMPC_GOV_A_HI;
    localparam [4:0]  GOV_KSH = `EMPC_GOV_KSH;
    localparam        GOV_EN = (`EMPC_GOV_EN != 0);
    localparam [31:0] GOV_CFG = {19'd0, GOV_KSH, 7'd0, GOV_EN};
    initial begin
        for (mi = 0; mi < 4096; mi = mi + 1) mem[mi] = 1'b0;
        for (mi = 0; mi < 32; mi = mi + 1) begin           // field 7 of slots 0..4: governor words
            mem[{4'd0, 3'd7, mi[4:0]}] = GOV_VMAX_LO[mi];
            mem[{4'd1, 3'd7, mi[4:0]}] = GOV_VMAX_HI[mi];
            mem[{4'd2, 3'd7, mi[4:0]}] = GOV_A_LO[mi];
            mem[{4'd3, 3'd7, mi[4:0]}] = GOV_A_HI[mi];
            mem[{4'd4, 3'd7, mi[4:0]}] = GOV_CFG[mi];
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
    reg  [11:0] rb_addr;                               // port B: {slot, field, bit}
    reg         rb_q;
    always @(posedge clk) rb_q <= mem[rb_addr];

    // ---------------- delay line (SRL) ----------------
    localparam integer DL = (N + 1) * 64;
    reg  [DL-1:0] dl;
    reg           dl_sh;
    reg           dl_in;
    always @(posedge clk) if (dl_sh) dl <= {dl[DL-2:0], dl_in};
    // one read port: bit 63 (the old head bit j in clock j of a pass) while the delay
    // line shifts, bit j of the head (63 - j) in a governed head pass (the delay line stands
    // still), else bit 63 - rd_bit of word rd_age (64 * age + 63 - bit)
    wire          dl_busy, g_head;
    wire [5:0]    jcw;
    wire [AW+5:0] rd_idx = dl_busy ? {{AW{1'b0}}, 6'd63} : g_head ? {{AW{1'b0}}, ~jcw} : {rd_age, ~rd_bit};
    wire          tap = dl[rd_idx];
    assign rd_q = tap;

    // ---------------- governor words (SRL): target rt, increment v, scratch sa, sb ----------------
    // Each shifts LSB first like the delay line: bit j of the old word leaves at [63] in clock j.
    reg  [63:0]   rt, v, sa, sb;
    reg           rt_sh, v_sh, sa_sh, sb_sh;
    reg           rt_in, v_in, sa_in, sb_in;
    always @(posedge clk) begin
        if (rt_sh) rt <= {rt[62:0], rt_in};
        if (v_sh)  v  <= {v[62:0], v_in};
        if (sa_sh) sa <= {sa[62:0], sa_in};
        if (sb_sh) sb <= {sb[62:0], sb_in};
    end
    reg  [4:0]    ksh;                                 // latched when an advance begins
    wire          rt_o = rt[63], v_o = v[63], sa_o = sa[63];
    wire          sb_t = sb[{1'b1, ~ksh}];             // bit j + ksh of sb in clock j (63 - ksh)

    // ---------------- engine ----------------
    localparam [3:0] K_FLG = 4'd0, K_HEAD = 4'd1, K_D1 = 4'd2, K_D2 = 4'd3, K_LEN = 4'd4, K_SYNC = 4'd5,
                     K_G1 = 4'd6, K_G2 = 4'd7, K_G3 = 4'd8, K_G4 = 4'd9;
    reg         run;                                   // a pass is running
    reg  [3:0]  kind;
    reg         act;                                   // past the lead clock
    reg  [5:0]  t;                                     // bit issued (address) in this clock
    reg  [5:0]  jc;                                    // bit consumed in this clock (act = 1)
    reg  [AW-1:0] cp;                                  // sync: copies still to run
    reg         m_load, m_hold, m_rel;
    reg         adv_pend, sync_pend, rst_sync;
    reg         pend;
    reg  [3:0]  pend_slot, slot, ld_slot;
    reg  [63:0] d1;
    reg  [31:0] d2, rem;
    reg         ends, last_r, last_nx, rem_one, one_acc;
    reg         ch, cd, br, d2s;
    // governor: enable (register, written by the CPU through field 7 of slot 4) and its copy
    // for the running advance, hold / task, carries k0..k2, clamp flags
    reg         gen_r;
    reg  [4:0]  gksh_r;
    reg         g_on, gv_hold, gv_pos;
    reg         k0, k1, k2;
    reg         e_sgn, ovr, x_sgn;                     // sign of e, sb tap past bit 63, sign of x1 / vdc
    reg         hi1, lo1, hi2, lo2, s2, v_nz, v_sgn, dv_nz;
    assign jcw = jc;

    wire        gk   = (kind == K_G1) || (kind == K_G2) || (kind == K_G3) || (kind == K_G4);
    wire [5:0]  jlast = (kind == K_FLG) ? 6'd1 : (kind == K_D2 || kind == K_LEN) ? 6'd31 : 6'd63;
    wire        last_bit = act && (jc == jlast);
    wire        seg_end  = ends && rem_one;
    // field of the bit issued in this clock
    wire [2:0]  fld = (kind == K_FLG) ? F_FLAGS : (kind == K_HEAD) ? (F_R0 + {2'b00, t[5]}) :
                      (kind == K_D1) ? (F_D1 + {2'b00, t[5]}) : (kind == K_D2) ? F_D2 :
                      gk ? 3'd7 : F_LEN;
    // governor words: vmax in slots 0/1 (G1, G2), a in slots 2/3 (G3, G4); bit 63 reads as 0
    wire [3:0]  g_slot = {2'b00, (kind == K_G3) || (kind == K_G4), t[5]};
    wire        pm = rb_q && (jc != 6'd63);            // vmax / a bit jc

    // head pass arithmetic (bit jc)
    wire        d1b  = d1[0];
    wire        d2x  = (jc[5] ? d2s : d2[0]);
    wire        h1   = rt_o ^ d1b ^ ch;
    wire        d1n  = d1b ^ d2x ^ cd;
    wire        remn = rem[0] ^ br;
    assign      sync_idx = jc;
    wire        sync_in  = !rst_sync && sync_bit;
    wire        in_head = (kind == K_SYNC) ? ((cp == N[AW-1:0]) ? sync_in : tap) :
                          (m_load && !m_rel) ? rb_q : h1;
    wire        normal  = !m_load && !m_hold;
    assign      g_head  = run && (kind == K_HEAD) && g_on;
    wire        first_sync = run && act && (kind == K_SYNC) && (cp == N[AW-1:0]);

    // governor pass arithmetic (bit jc); k0..k2 are the carries of the pass's adders
    //   head: x1 = r_new - r_old -> sa (k0), e = r_old - g -> sb (k1)
    wire        x1b  = in_head ^ ~rt_o ^ k0;
    wire        eb   = rt_o ^ ~tap ^ k1;
    //   G1: vd = x1 + (e >>> ksh) -> sa (k0); vd + ~vmax (k1), vd + vmax (k2): the clamps
    wire        esb  = ovr ? e_sgn : sb_t;
    wire        vdb  = sa_o ^ esb ^ k0;
    //   G2: vdc = clamp(vd) (-vmax = ~vmax + 1: k1), dv = vdc + ~v + 1 -> sb (k0)
    wire        nvm  = ~pm ^ k1;
    wire        vdc  = (gv_hold && !gv_pos) ? 1'b0 : hi1 ? pm : lo1 ? nvm : sa_o;
    wire        dvb  = vdc ^ ~v_o ^ k0;
    //   G3: dv + ~a (k1), dv + a (k2): the clamps; dv recirculates in sb
    //   G4: dvc = clamp(dv) (-a: k1) or 0 (hold), v' = v + dvc (k0), g' = g + v' (k2) -> delay line
    wire        na   = ~pm ^ k1;
    wire        blk  = gv_hold && gv_pos && dv_nz && v_nz && (s2 == v_sgn);
    wire        dvc  = blk ? 1'b0 : hi2 ? pm : lo2 ? na : sb[63];
    wire        vnb  = v_o ^ dvc ^ k0;
    wire        gnb  = tap ^ vnb ^ k2;
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
        rb_addr = gk ? {g_slot, fld, t[4:0]} : {ld_slot, fld, t[4:0]};
        // rt: the new target in the head pass, the sync value in the first sync pass
        rt_sh = run && act && (kind == K_HEAD || (kind == K_SYNC && cp == N[AW-1:0]));
        rt_in = in_head;
        // v: 0 in a head pass without the governor and in the first sync pass, v' in G4,
        // recirculates in G2
        v_sh  = run && act && ((kind == K_HEAD && !g_on) || first_sync || kind == K_G2 || kind == K_G4);
        v_in  = (kind == K_G4) ? vnb : (kind == K_G2) ? v_o : 1'b0;
        sa_sh = run && act && ((kind == K_HEAD && g_on) || kind == K_G1 || kind == K_G2);
        sa_in = (kind == K_G1) ? vdb : (kind == K_G2) ? sa_o : x1b;
        sb_sh = run && act && ((kind == K_HEAD && g_on) || gk);
        sb_in = (kind == K_HEAD) ? eb : (kind == K_G2) ? dvb : sb[63];
    end

    assign dl_busy = run && (kind == K_SYNC || (kind == K_HEAD && !g_on) || kind == K_G4);
    assign busy = run || adv_pend || sync_pend;
    assign w_ok = !adv_pend && !sync_pend &&
                  !(run && (kind == K_FLG || kind == K_HEAD || kind == K_SYNC || gk));

    // operation start (engine idle)
    wire        go_sync = !run && sync_pend;
    wire        go_adv  = !run && !sync_pend && adv_pend;
    wire        g_load  = pend || (seg_end && !last_r);
    wire        g_hold  = !pend && seg_end && last_r;
    wire        zero_dif = rst || go_sync || (run && m_hold && kind == K_HEAD && last_bit);

    // governor enable / ksh register: a copy of field 7 of slot 4 (written with it by the CPU,
    // initialised with it at configuration, kept over rst like the slot memory)
    initial begin
        gen_r = GOV_EN;
        gksh_r = GOV_KSH;
    end
    always @(posedge clk) begin
        if (seg_we && seg_field == 3'd7 && seg_slot == 4'd4) begin
            gen_r <= seg_wdata[0];
            gksh_r <= seg_wdata[12:8];
        end
    end

    always @(posedge clk) begin
        gov_ev <= 1'b0;
        if (rst) begin
            run <= 1'b1;                               // clear the delay line: sync to 0
            kind <= K_SYNC;
            act <= 1'b0;
            t <= 6'd0;
            jc <= 6'd0;
            cp <= N[AW-1:0];
            rst_sync <= 1'b1;
            adv_pend <= 1'b0;
            sync_pend <= 1'b0;
            pend <= 1'b0;
            pend_slot <= 4'd0;
            slot <= 4'd0;
            ld_slot <= 4'd0;
            m_load <= 1'b0;
            m_hold <= 1'b0;
            m_rel <= 1'b0;
            last_r <= 1'b0;
            last_nx <= 1'b0;
            rem_one <= 1'b0;
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
        end else begin
            if (advance) adv_pend <= 1'b1;
            if (sync) sync_pend <= 1'b1;
            if (start) begin
                pend <= 1'b1;
                pend_slot <= start_slot;
            end
            if (!run) begin
                t <= 6'd0;
                act <= 1'b0;
                if (go_sync) begin
                    sync_pend <= sync;                 // a sync in this clock runs again after
                    run <= 1'b1;
                    kind <= K_SYNC;
                    cp <= N[AW-1:0];
                    rst_sync <= 1'b0;
                    last_r <= 1'b0;
                end else if (go_adv) begin
                    adv_pend <= advance;
                    run <= 1'b1;
                    m_load <= g_load;
                    m_hold <= g_hold;
                    m_rel <= 1'b0;
                    ld_slot <= pend ? pend_slot : slot + 4'd1;
                    if (pend && !start) pend <= 1'b0;
                    kind <= g_load ? K_FLG : K_HEAD;
                    g_on <= gen_r;
                    ksh <= gksh_r;
                    gv_hold <= hold;
                    gv_pos <= task_pos;
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
                            if (jc == 6'd31) d2s <= d2[0];
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
                    br <= br & !rem[0];
                    k0 <= k0n;
                    k1 <= k1n;
                    k2 <= k2n;
                    if (kind == K_HEAD && normal && !jc[5]) begin
                        if (jc == 6'd0) one_acc <= remn;
                        else if (remn) one_acc <= 1'b0;
                    end
                    // governor bookkeeping
                    if (kind == K_HEAD && jc == 6'd63) e_sgn <= eb;
                    if (kind == K_G1 && jc == {1'b1, ~ksh}) ovr <= 1'b1;
                    if (kind == K_G2) begin
                        if (v_o) v_nz <= 1'b1;
                        if (jc == 6'd63) begin
                            v_sgn <= v_o;
                            s2 <= ov2 ? vdc : dvb;              // sign of the exact vdc - v
                            x_sgn <= ov2;                       // (overflowed: the clamp is certain)
                        end
                    end
                    if (kind == K_G3 && sb[63]) dv_nz <= 1'b1;
                    if (jc == 6'd63) begin
                        if (kind == K_G1) begin                 // exact vd: 65-bit sign if overflowed
                            hi1 <= ov1 ? !sa_o : (vdb ^ c_hi);
                            lo1 <= ov1 ? sa_o : (vdb ^ c_lo);
                        end
                        if (kind == K_G3) begin
                            hi2 <= x_sgn ? !s2 : (sb[63] ^ c_hi);
                            lo2 <= x_sgn ? s2 : (sb[63] ^ c_lo);
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
                    if (kind == K_G2) v_nz <= 1'b0;
                    if (kind == K_G3) dv_nz <= 1'b0;
                end
                if (last_bit) begin
                    t <= 6'd0;
                    act <= 1'b0;
                    case (kind)
                        K_FLG: kind <= K_HEAD;
                        K_HEAD: begin
                            if (!m_load) rem_one <= normal && ends && one_acc;
                            if (g_on) kind <= K_G1;
                            else if (m_load) kind <= K_D1;
                            else run <= 1'b0;
                        end
                        K_G1: kind <= K_G2;
                        K_G2: kind <= K_G3;
                        K_G3: kind <= K_G4;
                        K_G4: begin
                            gov_ev <= gv_hold || hi1 || lo1 || hi2 || lo2;
                            if (m_load) kind <= K_D1;
                            else run <= 1'b0;
                        end
                        K_D1: kind <= K_D2;
                        K_D2: kind <= K_LEN;
                        K_LEN: begin
                            run <= 1'b0;
                            rem_one <= one_acc && !rb_q;   // len == 1 (bit 31 is this clock's)
                            last_r <= last_nx;
                            slot <= ld_slot;
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

    // state shift registers (d1 64, d2 32, rem 32: LSB out first)
    always @(posedge clk) begin
        if (zero_dif) begin
            d1 <= 64'd0;
            d2 <= 32'd0;
            rem <= 32'd0;
            ends <= 1'b0;
        end else if (run && act) begin
            case (kind)
                K_HEAD: begin
                    d1 <= {normal ? d1n : 1'b0, d1[63:1]};
                    if (normal && !jc[5]) begin
                        d2 <= {d2[0], d2[31:1]};
                        rem <= {remn, rem[31:1]};
                    end
                end
                K_D1: d1 <= {rb_q, d1[63:1]};
                K_D2: d2 <= {rb_q, d2[31:1]};
                K_LEN: begin
                    rem <= {rb_q, rem[31:1]};
                    if (jc == 6'd0) ends <= rb_q;
                    else if (rb_q) ends <= 1'b1;
                end
                default: ;
            endcase
        end
    end

`ifndef SYNTHESIS
    initial begin
        if (N < 1) $display("ERROR: ref_gen N=%0d must be >= 1", N);
    end
`endif
endmodule
`default_nettype wire
