// mx_seq: the control sequencer of the axis (paper 000 Fig. 3, sec. V-A) on a word-parallel
// microprogrammed ALU (docs/four_axes.md 3.4, docs/blocks/mx_seq.md).  Replaces the bit-serial
// ctrl_seq; computes exactly gen/empc/rtlmodel/ctrl_seq.py (CtrlSeq.period, its speed estimate;
// field weakening and the governor's hold stay in mpc_axis).
//
// Per PWM period (a "job" of the job's axis):
//   boundary (period_start): decide whether the coming sample is a control sample
//       (pwm_per_control) and, if so, pulse ctl_boundary (combinational, in the clock of
//       period_start: mpc_axis decides a pending coefficient swap there, so task_pos and the bank
//       are the new ones before the advance takes task_pos and before the trigger picks the
//       program) and advance the references (ref_advance, one clock later: D5, the reference work
//       leaves the latency path); after ref_gen's w_ok the N + 1 references are read (bit-serially,
//       ref_age / ref_bit -> ref_q) into the axis state RAM: 2 words per reference
//   trigger (adc_trig, the centre sample): latch the count, THETA_LAT clocks later the angle, start
//       the program of the period: control (speed or position task: the words that need no current,
//       theta_mod), or modulation only
//   ADC valid: xform front (Clarke, Park) with theta_trig -> i_d, i_q; the dependent part of the
//       program (y, dx, the speed estimate omega = sat32(spd + ka - D), dx2), core start; while the
//       core runs: previous-sample words, status words, the load estimate D
//   core done (or, law off, at once): xform mod with the held u and theta_mod -> cmp, cmp_load
//   latency = clocks from the trigger to cmp_load; overrun when a boundary meets a running job.
//
// ALU (one 32/48-bit word per clock): issue (microword from the program block RAM; RAM port B read
// of the job's axis {axis, word}; the A source staged into a register cleared unless selected),
// E (A = OR of the stages or the last result P shifted by 0/1/8/16 (no other source is shifted:
// the model's Op.word() asserts it), B = the RAM word or its bits
// 31:16 / 31:24 with their rounding bit, R = +-A +-B + cin), W (sat32 / wrap32 / wrap36 of R to the
// core input buffer, the axis state RAM port A, a status word, the omega / theta_mod registers or
// the serial shifter).  kacc * i_q is a product of xform's DSP48A1 (mul_b, prod: the front's end, held); the rounding shifts (kacc_shift,
// load_shift + 1) are a 40-bit serial right shifter, one bit per clock.  Program and hazards: the
// tables of gen/empc/rtlmodel/mx_seq.py (rtl/mx_seq_ucode.vh, rtl/mx_seq_rom.vh).
//
// Axes: the state RAM is addressed {axis, word} (AXB axis bits); with NAXES = 1 the job's axis is 0.
// The job queue of several axes (one trigger-pending / ADC-valid-pending flag per axis, jobs in
// sample order) is not built: the ports are one axis's (docs/blocks/mx_seq.md, "four axes").
//
// Ports: as ctrl_seq's, except the status words: st_we / st_addr / st_wdata write one 32-bit word
// (axis_status; st_addr / st_wdata are held until the next status or core write, >= 2 clocks
// later, so axis_status's deferred write takes them from the ports in the clock after st_we); stat_sweep pulses when a control period's job ends (cmp_load): axis_status counts
// the period's events then.  ctl_boundary (new): the swap decision point of the core's bank
// (swap_at), = period_start && the coming sample is a control sample, combinational from
// period_start and registers.  core_in_*, st_* and the ref_* read addresses are registered.
// Latency: trigger -> cmp_load on `latency`; from the ADC's valid: 1 (front request) + 23 (front)
// + the dependent program (21 + kacc_shift clocks) + 1 + the core (38 + columns) + 1 + 85 (mod).
// Reset: idle, first period flagged, the axis state RAM cleared by a 32 x NAXES-clock sweep, the
// reference prefetch re-armed (it waits for ref_gen's w_ok).
`default_nettype none
`include "empc_formats.vh"
`include "empc_regs.vh"
module mx_seq #(
    parameter integer N = `EMPC_N,
    parameter integer CW = $clog2(`EMPC_PWM_HALF_PERIOD + 1),
    parameter integer THETA_LAT = 4,    // pos_sense: clocks from a count to its angle (1..8)
    parameter integer NAXES = 1,
    parameter integer AXB = (NAXES < 2) ? 1 : $clog2(NAXES),
    parameter integer AW = (N < 2) ? 1 : $clog2(N + 1)
) (
    input  wire                           clk,
    input  wire                           rst,
    // timing
    input  wire                           adc_trig,        // PWM period centre
    input  wire                           period_start,    // PWM period boundary
    input  wire [7:0]                     pwm_per_control,
    input  wire                           run,             // control law active
    // measurements
    input  wire [`EMPC_ANGLE_BITS-1:0]    theta,
    input  wire [`EMPC_POS_W-1:0]         pos,
    output reg                            pos_sample,
    input  wire                           adc_valid,
    input  wire signed [`EMPC_ADC_BITS:0] cur0,
    input  wire signed [`EMPC_ADC_BITS:0] cur1,
    input  wire signed [`EMPC_ADC_BITS:0] cur2,
    // registers
    input  wire [17:0]                    kdc,
    input  wire signed [17:0]             kacc,
    input  wire [4:0]                     kacc_shift,
    input  wire [3:0]                     load_shift,
    input  wire signed [`EMPC_I_W-1:0]    id_ref,
    input  wire signed [`EMPC_I_W-1:0]    iq_ref,
    input  wire                           task_pos,
    // reference generator
    output wire                           ctl_boundary,    // boundary before a control sample (pulse)
    output reg                            ref_advance,
    input  wire                           ref_ok,
    output wire [AW-1:0]                  ref_age,
    output wire [5:0]                     ref_bit,
    input  wire                           ref_q,
    // MPC core
    output reg                            core_start,
    output reg                            core_in_we,
    output reg  [5:0]                     core_in_addr,
    output reg  signed [`EMPC_SIG_W-1:0]  core_in_wdata,
    input  wire                           core_done,
    input  wire [2*`EMPC_U_W-1:0]         core_u,
    input  wire [3*`EMPC_SIG_W-1:0]       core_ebar,
    // PWM
    output wire [3*CW-1:0]                cmp,
    output reg                            cmp_load,
    // status
    output reg                            control_done,
    output reg                            overrun,
    output reg                            front_sat,
    output reg  [15:0]                    latency,
    output wire signed [`EMPC_I_W-1:0]    i_d,
    output wire signed [`EMPC_I_W-1:0]    i_q,
    output reg  signed [`EMPC_W_W-1:0]    omega,
    output reg  [`EMPC_ANGLE_BITS-1:0]    theta_trig,
    output reg                            st_we,
    output reg  [5:0]                     st_addr,
    output reg  [31:0]                    st_wdata,
    output reg                            stat_sweep
);
    localparam integer SW = `EMPC_SIG_W;     // 32
    localparam integer UW = `EMPC_U_W;       // 24
    localparam integer IW = `EMPC_I_W;       // 18
    localparam integer AB = `EMPC_ANGLE_BITS; // 16
    localparam integer PW = `EMPC_POS_W;     // 32
    localparam integer XW = 48;              // ALU width
    localparam integer SHW = 40;             // serial shifter: |kacc i_q| < 2^35, |t2| < 2^37 (D wraps at 36 bits)
    localparam integer RW = 36;              // axis state RAM word
    localparam integer NREF = 64 * (N + 1);  // reference bits read after an advance
    localparam integer PFB = $clog2(NREF);
`include "mx_seq_ucode.vh"

    generate if (SW != 32 || UW != 24 || IW != 18 || `EMPC_W_W != 32 || PW != 32 || AB != 16 || N > 8 || N < 1 ||
                 THETA_LAT < 1 || THETA_LAT > 8 || NAXES != 1 || !UC_MAP_OK)
    begin : g_bad_params
        mx_seq_unsupported_parameters u_error ();   // no such module: elaboration stops here
    end endgenerate

    // ================================ period bookkeeping ================================
    reg  [7:0]  per_nx;             // PWM periods since the last control period, + 1 (mod 256)
    reg         ctl_next;           // the coming sample is a control sample (decided at the boundary)
    reg         is_control, first, mfirst, busy_period;
    reg  [15:0] lat_cnt;            // clocks since the trigger, + 1 (one adder: latency takes it as is)
    reg  [PW-1:0] pos_trig;
    reg  signed [UW-1:0] u_st0, u_st1;
    reg         zeroed;
    reg         th_wait, th_ok, adc_seen, front_go, front_done, core_run, core_fin;
    reg  [2:0]  th_cnt;
    reg  [AXB-1:0] ax;              // the job's axis (NAXES = 1: 0)
    wire        trig = adc_trig && !busy_period;
    // the coming sample is a control sample: the compare registered, so that ctl_boundary is one gate
    // from registers into the core's swap logic (18 LUT less in the drive).  One clock old: per_nx
    // changes at a trigger; a pwm_per_control write (bridges off only) in the clock before a boundary
    // takes effect at the next one, for ctl_next, the advance and the swap alike
    reg         ctl_now;
    always @(posedge clk) ctl_now <= !rst && (per_nx >= pwm_per_control);
    assign      ctl_boundary = period_start && ctl_now;
    wire [7:0]  per_cnt = per_nx - 8'd1;    // (read by tb/hdl/cosim_top.v only)

    // transform chain (xform): front with theta_trig, mod with theta_mod and the held u
    reg  xf_front, xf_mod, xf_run_mod;
    wire xf_busy, xf_done, xf_sat;
    wire [CW-1:0] cmp_a, cmp_b, cmp_c;
    wire signed [35:0] pr;          // kacc * i_q on xform's multiplier, after the front
    reg  [AB-1:0] th_mod;
    wire [AB-1:0] ang = xf_front ? theta_trig : th_mod;
    xform u_xform (.clk(clk), .rst(rst), .start_front(xf_front), .start_mod(xf_mod), .angle(ang),
                   .i_a(cur0), .i_b(cur1), .i_c(cur2), .u_d(u_st0), .u_q(u_st1), .kdc(kdc), .mul_b(kacc),
                   .busy(xf_busy), .done(xf_done), .sat(xf_sat), .i_d(i_d), .i_q(i_q),
                   .cmp_a(cmp_a), .cmp_b(cmp_b), .cmp_c(cmp_c), .prod(pr));
    assign cmp = {cmp_c, cmp_b, cmp_a};

    // engine actions (W stage of the ALU, below)
    wire        a_start, a_mod, a_end, eng_sat;

    always @(posedge clk) begin
        xf_front <= 1'b0;
        xf_mod <= 1'b0;
        core_start <= 1'b0;
        cmp_load <= 1'b0;
        pos_sample <= 1'b0;
        ref_advance <= 1'b0;
        control_done <= 1'b0;
        overrun <= 1'b0;
        front_sat <= 1'b0;
        stat_sweep <= 1'b0;
        if (rst) begin
            ctl_next <= 1'b0;
            is_control <= 1'b0;
            first <= 1'b1;
            mfirst <= 1'b1;
            busy_period <= 1'b0;
            latency <= 16'd0;
            pos_trig <= {PW{1'b0}};
            theta_trig <= {AB{1'b0}};
            zeroed <= 1'b1;
            th_wait <= 1'b0;
            th_ok <= 1'b0;
            adc_seen <= 1'b0;
            front_go <= 1'b0;
            front_done <= 1'b0;
            core_run <= 1'b0;
            core_fin <= 1'b0;
            xf_run_mod <= 1'b0;
            ax <= {AXB{1'b0}};
        end else begin
            if (period_start && busy_period)
                overrun <= 1'b1;
            zeroed <= core_done ? 1'b0 : (!run ? 1'b1 : zeroed);
            // ---- boundary: the coming sample's kind; the references advance now ----
            if (period_start) begin
                ctl_next <= ctl_now;
                ref_advance <= ctl_now;
            end
            // ---- trigger ----
            if (trig) begin
                mfirst <= first;
                first <= 1'b0;
                busy_period <= 1'b1;
                is_control <= ctl_next;
                th_wait <= 1'b1;
                th_ok <= 1'b0;
                adc_seen <= 1'b0;
                front_go <= 1'b0;
                front_done <= 1'b0;
                core_fin <= !ctl_next;          // a modulation-only period needs no core
                if (ctl_next) begin
                    pos_sample <= 1'b1;
                    pos_trig <= pos;
                end
            end
            if (th_wait && th_cnt == 3'd0) begin
                theta_trig <= theta;
                th_wait <= 1'b0;
                th_ok <= 1'b1;
            end
            // ---- ADC, front ----
            if (busy_period && adc_valid) adc_seen <= 1'b1;
            if (is_control && busy_period && adc_seen && th_ok && !front_go && !xf_busy) begin
                xf_front <= 1'b1;
                front_go <= 1'b1;
            end
            if (xf_done && !xf_run_mod && is_control) begin
                front_done <= 1'b1;
                if (xf_sat) front_sat <= 1'b1;
            end
            if (eng_sat) front_sat <= 1'b1;
            // ---- core ----
            if (a_start) begin
                if (run) begin
                    core_start <= 1'b1;
                    core_run <= 1'b1;
                end else begin
                    core_fin <= 1'b1;
                    control_done <= 1'b1;
                end
            end
            if (core_run && core_done) begin
                core_run <= 1'b0;
                core_fin <= 1'b1;
                control_done <= 1'b1;
            end
            // ---- modulation ----
            if (a_mod) xf_mod <= 1'b1;
            if (xf_mod && !xf_busy) xf_run_mod <= 1'b1;
            if (xf_done && xf_run_mod) begin
                xf_run_mod <= 1'b0;
                if (xf_sat) front_sat <= 1'b1;
                cmp_load <= 1'b1;
                stat_sweep <= is_control;
                latency <= lat_cnt;
                busy_period <= 1'b0;
            end
        end
    end
    always @(posedge clk) begin
        if (rst || (trig && ctl_next))
            per_nx <= 8'd1;
        else if (trig)
            per_nx <= per_nx + 8'd1;
        if (trig)
            lat_cnt <= 16'd1;
        else if (busy_period)
            lat_cnt <= lat_cnt + 16'd1;
        if (trig)
            th_cnt <= THETA_LAT[2:0] - 3'd1;
        else if (th_wait)
            th_cnt <= th_cnt - 3'd1;
    end
    // held u: loaded at core_done, 0 while run is low
    always @(posedge clk) begin
        if (rst || (!run && !core_done)) begin
            u_st0 <= {UW{1'b0}};
            u_st1 <= {UW{1'b0}};
        end else if (core_done) begin
            u_st0 <= core_u[0 +: UW];
            u_st1 <= core_u[UW +: UW];
        end
    end

    // ===================================== engine =====================================
    (* rom_style = "block" *) reg [35:0] rom [0:255];
    integer ui;
    initial begin
`include "mx_seq_rom.vh"
    end
    reg  [7:0]  pc, pc_next;
    reg  [35:0] iw;                 // rom[pc] (block RAM output register)
    reg         prun;               // a program is running
    reg         refs_ok, refs_taken;
    reg         sh_busy;
    wire [2:0]  i_ctl = iw[UW_CTL +: 3];
    reg         cond_ok;
    always @(*) begin
        case (i_ctl)
            CTL_WTH:    cond_ok = th_ok;
            CTL_WREF:   cond_ok = refs_ok;
            CTL_WFRONT: cond_ok = front_done;
            CTL_WSH:    cond_ok = !sh_busy;
            CTL_WCORE:  cond_ok = core_fin;
            default:    cond_ok = 1'b1;
        endcase
    end
    wire        issue = prun && cond_ok;
    always @(*) begin
        if (trig) pc_next = !ctl_next ? PC_MOD : task_pos ? PC_POS : PC_SPD;
        else if (issue) pc_next = pc + 8'd1;
        else pc_next = pc;
    end
    always @(posedge clk) iw <= rom[pc_next];
    always @(posedge clk) begin
        if (rst) begin
            pc <= 8'd0;
            prun <= 1'b0;
            refs_taken <= 1'b0;
        end else begin
            pc <= pc_next;
            if (trig) begin
                prun <= 1'b1;
                refs_taken <= 1'b0;
            end else if (issue && i_ctl == CTL_END) begin
                prun <= 1'b0;
            end
            if (issue && i_ctl == CTL_WREF) refs_taken <= 1'b1;
        end
    end

    // ---------------- issue: RAM read, staged A sources ----------------
    wire [3:0]  i_as = iw[UW_ASEL +: 4];
    (* ram_style = "block" *) reg [RW-1:0] sram [0:(32<<AXB)-1];   // axis state RAM {axis, word}
    reg  [RW-1:0] q;
    always @(posedge clk) q <= sram[{ax, iw[UW_RB +: 5]}];
    // stages: the selected source in the clock after its issue, 0 otherwise
    reg  [PW-1:0] g_pos;
    reg  [AB-1:0] g_th;
    reg  [IW-1:0] g_id, g_iq, g_idr, g_iqr;
    reg  [UW-1:0] g_u0, g_u1;
    reg  [SW-1:0] g_e0, g_e1, g_e2, g_om;
    reg  [35:0]   g_pr;
    reg  [SHW-1:0] g_sh;
    reg           g_p;
    wire          zeroed_nx = rst || (!core_done && (!run || zeroed));
    reg  signed [SHW-1:0] sh;               // serial shifter
    always @(posedge clk) begin
        g_pos <= (issue && i_as == AS_POS) ? pos_trig : {PW{1'b0}};
        g_th  <= (issue && i_as == AS_TH)  ? theta_trig : {AB{1'b0}};
        g_id  <= (issue && i_as == AS_ID)  ? i_d : {IW{1'b0}};
        g_iq  <= (issue && i_as == AS_IQ)  ? i_q : {IW{1'b0}};
        g_idr <= (issue && i_as == AS_IDR) ? id_ref : {IW{1'b0}};
        g_iqr <= (issue && i_as == AS_IQR) ? iq_ref : {IW{1'b0}};
        g_u0  <= (issue && i_as == AS_U0)  ? u_st0 : {UW{1'b0}};
        g_u1  <= (issue && i_as == AS_U1)  ? u_st1 : {UW{1'b0}};
        g_e0  <= (issue && i_as == AS_E0 && !zeroed_nx) ? core_ebar[0*SW +: SW] : {SW{1'b0}};
        g_e1  <= (issue && i_as == AS_E1 && !zeroed_nx) ? core_ebar[1*SW +: SW] : {SW{1'b0}};
        g_e2  <= (issue && i_as == AS_E2 && !zeroed_nx) ? core_ebar[2*SW +: SW] : {SW{1'b0}};
        g_om  <= (issue && i_as == AS_OMR) ? omega : {SW{1'b0}};
        g_pr  <= (issue && i_as == AS_PR)  ? pr : 36'd0;
        g_sh  <= (issue && i_as == AS_SH)  ? sh : {SHW{1'b0}};
        g_p   <= issue && i_as == AS_P;
    end
    // the rest of the microword, one stage per clock
    reg          e_v, e_aw, e_na, e_nb, e_rc, e_cr, e_pe, e_fs;
    reg  [1:0]   e_ash, e_bm, e_wm, e_cond;
    reg  [2:0]   e_dk, e_ctl;
    reg  [5:0]   e_da;
    always @(posedge clk) begin
        e_v   <= issue && !rst;
        e_aw  <= iw[UW_AW];
        e_ash <= iw[UW_ASH +: 2];
        e_na  <= iw[UW_NA];
        e_nb  <= iw[UW_NB];
        e_bm  <= iw[UW_BM +: 2];
        e_rc  <= iw[UW_RC];
        e_cr  <= iw[UW_CR];
        e_pe  <= iw[UW_PE];
        e_wm  <= iw[UW_WM +: 2];
        e_fs  <= iw[UW_FS];
        e_dk  <= iw[UW_DK +: 3];
        e_da  <= iw[UW_DA +: 6];
        e_cond <= iw[UW_COND +: 2];
        e_ctl <= i_ctl;
    end

    // ---------------- E: R = +-A +-B + cin ----------------
    reg  signed [XW-1:0] p_r;       // P: the last result with pe
    reg  signed [XW-1:0] r;         // R: this op's result (W stage)
    reg                  sh_r;      // the shifter's last bit out (rounding)
    // the shift of A (ash) applies to P only (2 theta: P = theta, then P << 1): the other
    // sources do not pass through the shift multiplexer
    wire [XW-1:0] p_w   = e_aw ? {{(XW-32){p_r[31]}}, p_r[31:0]} : p_r;
    reg  [XW-1:0] p_fwd;
    always @(*) begin
        if (!g_p)
            p_fwd = {XW{1'b0}};
        else case (e_ash)
            2'd0: p_fwd = p_w;
            2'd1: p_fwd = {p_w[XW-2:0], 1'b0};
            2'd2: p_fwd = {p_w[XW-9:0], 8'd0};
            default: p_fwd = {p_w[XW-17:0], 16'd0};
        endcase
    end
    wire [XW-1:0] a_or  = {{(XW-PW){g_pos[PW-1]}}, g_pos} | {{(XW-AB){1'b0}}, g_th} |
                          {{(XW-IW){g_id[IW-1] | g_iq[IW-1] | g_idr[IW-1] | g_iqr[IW-1]}}, g_id | g_iq | g_idr | g_iqr} |
                          {{(XW-UW){g_u0[UW-1] | g_u1[UW-1]}}, g_u0 | g_u1} |
                          {{(XW-SW){g_e0[SW-1] | g_e1[SW-1] | g_e2[SW-1] | g_om[SW-1]}}, g_e0 | g_e1 | g_e2 | g_om} |
                          {{(XW-36){g_pr[35]}}, g_pr} | {{(XW-SHW){g_sh[SHW-1]}}, g_sh} | p_fwd;
    wire [XW-1:0] a_sh  = a_or;
    reg  [XW-1:0] b_op;
    always @(*) begin
        case (e_bm)
            BM_ZERO: b_op = {XW{1'b0}};
            BM_Q:    b_op = {{(XW-RW){q[RW-1]}}, q};
            BM_HI16: b_op = {{(XW-16){1'b0}}, q[31:16]};
            default: b_op = {{(XW-8){1'b0}}, q[31:24]};
        endcase
    end
    wire          cin = e_na | e_nb | (e_rc & (e_bm[0] ? q[23] : q[15])) | (e_cr & sh_r);
    wire [XW-1:0] sum = (e_na ? ~a_sh : a_sh) + (e_nb ? ~b_op : b_op) + {{(XW-1){1'b0}}, cin};
    reg          w_v, w_fs;
    reg  [1:0]   w_wm, w_cond;
    reg  [2:0]   w_dk, w_ctl;
    reg  [5:0]   w_da;
    always @(posedge clk) begin
        if (e_v) r <= sum;
        if (e_v && e_pe) p_r <= sum;
        w_v <= e_v && !rst;
        w_fs <= e_fs;
        w_wm <= e_wm;
        w_cond <= e_cond;
        w_dk <= e_dk;
        w_ctl <= e_ctl;
        w_da <= e_da;
    end

    // ---------------- W: saturate / wrap, write ----------------
    wire          ovf = !(&r[XW-1:31] || !(|r[XW-1:31]));     // R does not fit 32 bits
    wire          sat_on = (w_wm == WM_SAT32) && ovf;
    wire [SW-1:0] w32 = sat_on ? {r[XW-1], {(SW-1){!r[XW-1]}}} : r[SW-1:0];
    // a RAM word is R's low 36 bits, or the saturated word: the program writes no other mode's
    // R wider than 32 bits there (the model does the same)
    wire [RW-1:0] w36 = {sat_on ? {(RW-SW){r[XW-1]}} : r[RW-1:SW], w32};
    reg           w_ok_c;
    always @(*) begin
        case (w_cond)
            CD_FIRST: w_ok_c = mfirst;
            CD_LS:    w_ok_c = (load_shift != 4'd0);
            CD_NOLS:  w_ok_c = (load_shift == 4'd0);
            default:  w_ok_c = 1'b1;
        endcase
    end
    wire          wen = w_v && w_ok_c;
    assign eng_sat = w_v && w_fs && w_wm == WM_SAT32 && ovf;
    assign a_start = w_v && w_ctl == CTL_START;
    assign a_mod   = w_v && w_ctl == CTL_WCORE;
    assign a_end   = w_v && w_ctl == CTL_END;
    always @(posedge clk) begin
        core_in_we <= wen && w_dk == DK_CORE;
        st_we <= wen && w_dk == DK_STAT && !rst;
        // one register pair for both (yosys merges identical registers): loaded by a core or status
        // write, so held after a status write until the next one (the schedule keeps it >= 2 issues
        // away: axis_status's deferred write takes them in the clock after st_we)
        if (wen && (w_dk == DK_CORE || w_dk == DK_STAT)) begin
            core_in_addr <= w_da;
            core_in_wdata <= w32;
            st_addr <= w_da;
            st_wdata <= w32;
        end
        if (rst) omega <= {SW{1'b0}};
        else if (wen && w_dk == DK_OMR) omega <= w32;
        if (wen && w_dk == DK_THM) th_mod <= w32[AB-1:0];
    end
    // serial shifter: loaded with R, then count steps of an arithmetic right shift (sh_r: the bit out)
    reg  [4:0]    sh_cnt;
    always @(posedge clk) begin
        if (wen && (w_dk == DK_SHKA || w_dk == DK_SHT2)) begin
            sh <= r[SHW-1:0];
            sh_r <= 1'b0;
            sh_cnt <= (w_dk == DK_SHKA) ? kacc_shift : ({1'b0, load_shift} + 5'd1);
            sh_busy <= (w_dk == DK_SHKA) ? (kacc_shift != 5'd0) : 1'b1;
        end else if (sh_busy) begin
            sh <= sh >>> 1;
            sh_r <= sh[0];
            sh_cnt <= sh_cnt - 5'd1;
            sh_busy <= (sh_cnt != 5'd1);
        end
        if (rst) sh_busy <= 1'b0;
    end

    // ---------------- axis state RAM: port A (ALU W stage, reference prefetch, clear after rst) ----------------
    reg  [5:0]    clr_cnt;              // 32 x NAXES words (NAXES = 1: 32)
    reg           clr;
    reg           pf_need, pf_act;
    reg  [1:0]    pf_g;
    reg  [PFB-1:0] pf_cnt;
    reg  [31:0]   pf_sr;
    wire          alu_ram = wen && w_dk == DK_RAM;
    wire          pf_go = pf_act && !alu_ram && !clr && (!busy_period || !refs_taken);
    wire [31:0]   pf_word = {ref_q, pf_sr[31:1]};
    wire          pf_wr = pf_go && (pf_cnt[4:0] == 5'd31);
    wire [4:0]    pf_wa = SW_REF0 + {pf_cnt[PFB-1:5]};
    assign ref_age = N[AW-1:0] - pf_cnt[PFB-1:6];
    assign ref_bit = pf_cnt[5:0];
    always @(posedge clk) begin
        if (clr)
            sram[{ax, clr_cnt[4:0]}] <= {RW{1'b0}};
        else if (alu_ram)
            sram[{ax, w_da[4:0]}] <= w36;
        else if (pf_wr)
            sram[{ax, pf_wa}] <= {{(RW-32){pf_word[31]}}, pf_word};
    end
    always @(posedge clk) begin
        if (rst) begin
            clr <= 1'b1;
            clr_cnt <= 6'd0;
        end else if (clr) begin
            clr_cnt <= clr_cnt + 6'd1;
            if (clr_cnt == 6'd31) clr <= 1'b0;
        end
    end
    // reference prefetch: after each advance (and after anything else that drops w_ok), read
    // w_k .. w_{k+N} into the RAM; refs_ok while they are current
    always @(posedge clk) begin
        if (rst || (period_start && ctl_now) || (!ref_ok && (pf_act || refs_ok))) begin
            pf_need <= 1'b1;
            pf_act <= 1'b0;
            refs_ok <= 1'b0;
            pf_g <= 2'd3;               // ref_gen's w_ok falls 2 clocks after our advance strobe
        end else begin
            if (pf_g != 2'd0) pf_g <= pf_g - 2'd1;
            if (pf_need && pf_g == 2'd0 && ref_ok) begin
                pf_need <= 1'b0;
                pf_act <= 1'b1;
            end
            if (pf_go && pf_cnt == NREF[PFB-1:0] - 1'b1) begin
                pf_act <= 1'b0;
                refs_ok <= 1'b1;
            end
        end
        if (!pf_act)
            pf_cnt <= {PFB{1'b0}};
        else if (pf_go) begin
            pf_cnt <= pf_cnt + 1'b1;
            pf_sr <= pf_word;
        end
    end

    wire unused = &{1'b0, a_end, per_cnt, pf_sr[0]};
endmodule
`default_nettype wire
