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
// Axes (NAXES = 1..4, docs/blocks/mx_seq.md "Several axes"): one engine, one job at a time.  Per axis
// a timing block (period-kind counter with its own pwm_per_control, ctl_boundary, the count latched at
// its trigger, its angle THETA_LAT clocks later, its ADC-valid flag, its trigger's clock count (the
// latency; NAXES = 1: a counter), its first flag, its reference prefetch flags); a job queue (a trigger
// that finds the engine busy waits with its place in the sample order, simultaneous triggers the lower
// axis first; the head starts in the clock of the running job's cmp_load; overrun[a] when a's boundary
// meets a's job waiting or running; model rtlmodel.mx_seq.schedule_axes) latches the job's axis `ax`,
// and every state RAM word, core input word ({ax, word}, start one-hot), status word ({ax, word}) and
// the per-axis measurements (vectors, element a at [a*W +: W]) are the job axis's; the registers (KDC,
// KACC, kacc_shift, load_shift, ID_REF, IQ_REF) come from outside, read at job_axis = ax (the register
// block's LUT RAM {axis, reg}).  The held u / ebar(k-1) of each axis are copied at its core_done into a
// block RAM word of the axis (the core's outputs are the last update's, of any axis).  One reference prefetch engine reads the axis of its latch (rd_age =
// {axis, age}), the lowest ready axis first.  NAXES = 1: the one-axis ports and behaviour, clock-exact.
//
// Ports: as ctrl_seq's, except the status words: st_we / st_addr / st_wdata write one 32-bit word
// (axis_status; st_addr / st_wdata are held until the next status or core write, >= 2 clocks
// later, so axis_status's deferred write takes them from the ports in the clock after st_we); stat_sweep pulses when a control period's job ends (cmp_load): axis_status counts
// the period's events then.  ctl_boundary (new): the swap decision point of the core's bank
// (swap_at), = period_start && the coming sample is a control sample, combinational from
// period_start and registers.  core_in_*, st_* and the ref_* read addresses are registered.
// Latency: trigger -> cmp_load on `latency`; from the ADC's valid: 1 (front request) + 23 (front)
// + the dependent program (21 + kacc_shift clocks) + 1 + the core (38 + columns) + 1 + 85 (mod).
// Speed window (KACC.win = m, control.speed_window M = 2^m; m > WL = `EMPC_WIN_LOG2_MAX acts as WL): per
// axis the counts of the last WD = `EMPC_WIN_DEPTH = 2^WL control samples in a shift register with a dynamic
// tap (WD = 16: 32 SRL LUTs per axis, no reset; a (WL+1)-bit count of the samples shifted in since rst
// gates the tap to 0 until it holds M of them, as the
// state RAM's pos_prev = 0 after its clear: the first M speeds after reset see pos_k - 0); the A
// source PH = pos_{k-M}; spd = sat32((pos - pos_{k-M}) << (16 - m)) as sat32(((dpos_M << 8) >>> m) << 8)
// and the load update (2 u1 >>> m) - (spd - spd_prev) >>> (load_shift + 1 - m) (>= 0) on the serial
// shifter (rtlmodel/ctrl_seq.py; equal to D += (2 u1 - M (spd - spd_prev)) >> (load_shift + 1) while
// load_shift + 1 >= m, which the configuration requires).  m = 0: eq. 37 as before, same latency.
// Reset: idle, every axis's first period flagged, the axis state RAM cleared by a 32 x NAXES-clock
// sweep, the reference prefetch re-armed (it waits for ref_gen's w_ok), the job queue empty.
`default_nettype none
`include "empc_formats.vh"
`include "empc_regs.vh"
module mx_seq #(
    parameter integer N = `EMPC_N,
    parameter integer CW = $clog2(`EMPC_PWM_HALF_PERIOD + 1),
    parameter integer THETA_LAT = 4,    // pos_sense: clocks from a count to its angle (1..8)
    parameter integer NAXES = 1,        // axes served (1..4); per-axis vectors: element a at [a*W +: W]
    parameter integer AXB = (NAXES < 2) ? 1 : $clog2(NAXES),
    parameter integer AW = (N < 2) ? 1 : $clog2(N + 1)
) (
    input  wire                           clk,
    input  wire                           rst,
    // timing (per axis)
    input  wire [NAXES-1:0]               adc_trig,        // PWM period centre of axis a
    input  wire [NAXES-1:0]               period_start,    // PWM period boundary of axis a
    input  wire [8*NAXES-1:0]             pwm_per_control,
    input  wire [NAXES-1:0]               run,             // control law active
    // measurements (per axis)
    input  wire [`EMPC_ANGLE_BITS*NAXES-1:0] theta,
    input  wire [`EMPC_POS_W*NAXES-1:0]   pos,
    output reg  [NAXES-1:0]               pos_sample,
    input  wire [NAXES-1:0]               adc_valid,
    input  wire [(`EMPC_ADC_BITS+1)*NAXES-1:0] cur0,
    input  wire [(`EMPC_ADC_BITS+1)*NAXES-1:0] cur1,
    input  wire [(`EMPC_ADC_BITS+1)*NAXES-1:0] cur2,
    // registers of the job's axis: read at job_axis = {axis} from the register block (docs/four_axes.md
    // 2.1: a LUT RAM {axis, reg} whose read address is job_axis; NAXES = 1: the axis's registers)
    output wire [AXB-1:0]                 job_axis,
    output wire [NAXES-1:0]               job_next,        // one-hot of job_axis's value in the next clock (its D)
    input  wire [17:0]                    kdc,
    input  wire [17:0]                    kacc,            // signed 18 bit
    input  wire [4:0]                     kacc_shift,
    input  wire [3:0]                     load_shift,
    input  wire [`EMPC_A_KACC_WIN_W-1:0]  win_shift,       // KACC.win: speed window M = 2^m (m > WL acts as WL)
    input  wire [`EMPC_I_W-1:0]           id_ref,          // signed
    input  wire [`EMPC_I_W-1:0]           iq_ref,
    input  wire [NAXES-1:0]               task_pos,
    // reference generator (ref_gen NAXES: per-axis strobes, the axis in the high bits of rd_age)
    output wire [NAXES-1:0]               ctl_boundary,    // boundary before a control sample (pulse)
    output reg  [NAXES-1:0]               ref_advance,
    input  wire [NAXES-1:0]               ref_ok,
    output wire [$clog2(NAXES)+AW-1:0]    ref_age,
    output wire [5:0]                     ref_bit,
    input  wire                           ref_q,
    // MPC core (mpc_core NAXES: start one-hot per axis, in_addr = {axis, word})
    output reg  [NAXES-1:0]               core_start,
    output reg                            core_in_we,
    output reg  [5+$clog2(NAXES):0]       core_in_addr,
    output reg  signed [`EMPC_SIG_W-1:0]  core_in_wdata,
    input  wire                           core_done,
    input  wire [2*`EMPC_U_W-1:0]         core_u,
    input  wire [3*`EMPC_SIG_W-1:0]       core_ebar,
    // PWM: cmp is the last job's, valid with its axis's cmp_load
    output wire [3*CW-1:0]                cmp,
    output reg  [NAXES-1:0]               cmp_load,
    // status (per axis; i_d, i_q, omega, theta_trig: the running or last job's)
    output reg  [NAXES-1:0]               control_done,
    output reg  [NAXES-1:0]               overrun,
    output reg  [NAXES-1:0]               front_sat,
    output reg  [16*NAXES-1:0]            latency,
    output wire signed [`EMPC_I_W-1:0]    i_d,
    output wire signed [`EMPC_I_W-1:0]    i_q,
    output reg  signed [`EMPC_W_W-1:0]    omega,
    output wire signed [`EMPC_W_W-1:0]    omega_next,      // omega's value in the next clock (its D)
    output wire [`EMPC_ANGLE_BITS-1:0]    theta_trig,
    output reg                            st_we,           // axis_status NAXES: st_addr = {axis, word}
    output reg  [5+$clog2(NAXES):0]       st_addr,
    output reg  [31:0]                    st_wdata,
    output reg  [NAXES-1:0]               stat_sweep
);
    localparam integer SW = `EMPC_SIG_W;     // 32
    localparam integer UW = `EMPC_U_W;       // 24
    localparam integer IW = `EMPC_I_W;       // 18
    localparam integer AB = `EMPC_ANGLE_BITS; // 16
    localparam integer PW = `EMPC_POS_W;     // 32
    localparam integer CUW = `EMPC_ADC_BITS + 1;   // 13: a phase current
    localparam integer XW = 48;              // ALU width
    localparam integer SHW = 40;             // serial shifter: |kacc i_q| < 2^35, |t2| < 2^37 (D wraps at 36 bits)
    localparam integer RW = 36;              // axis state RAM word
    localparam integer NREF = 64 * (N + 1);  // reference bits read after an advance
    localparam integer PFB = $clog2(NREF);
    localparam integer CLB = $clog2(32 * NAXES) + 1;   // the clear sweep's counter (NAXES = 1: 6)
    localparam integer CLR_LAST = 32 * NAXES - 1;
    localparam integer WL = `EMPC_WIN_LOG2_MAX;    // largest speed window m (formats.WIN_LOG2_MAX)
    localparam integer WD = `EMPC_WIN_DEPTH;       // count history per axis, 2^WL
    localparam integer WFW = `EMPC_A_KACC_WIN_W;   // the KACC.win field
    localparam [WFW-1:0] WLF = WL[WFW-1:0];         // WL in the field's width (the clamp)
`include "mx_seq_ucode.vh"

    generate if (SW != 32 || UW != 24 || IW != 18 || `EMPC_W_W != 32 || PW != 32 || AB != 16 || N > 8 || N < 1 ||
                 THETA_LAT < 1 || THETA_LAT > 8 || NAXES < 1 || NAXES > 4 || !UC_MAP_OK ||
                 WL < 1 || WL > 7 || WD != (1 << WL) || WL >= (1 << WFW))
    begin : g_bad_params
        mx_seq_unsupported_parameters u_error ();   // no such module: elaboration stops here
    end endgenerate

    // ================================ job state (one job at a time) ================================
    reg         is_control, mfirst, busy_period;
    reg         front_go, front_done, core_run, core_fin;
    reg  [AXB-1:0] ax;              // the job's axis (NAXES = 1: 0)
    wire [NAXES-1:0] ax_oh;         // one-hot of ax
    wire        jstart;             // a job starts (NAXES = 1: the trigger)
    wire [AXB-1:0] jax;             // its axis
    wire [NAXES-1:0] jst_oh;        // jstart, one-hot of jax

    // ================================ per-axis timing blocks ================================
    reg  [8*NAXES-1:0]  per_nx;     // PWM periods since the last control period, + 1 (mod 256)
    reg  [NAXES-1:0]    ctl_now;    // the coming sample would be a control sample (registered compare)
    reg  [NAXES-1:0]    ctl_next;   // the coming sample is a control sample (decided at the boundary)
    reg  [NAXES-1:0]    first;      // the axis's first period after rst
    reg  [NAXES-1:0]    tpend;      // a trigger waits in the job queue
    reg  [NAXES-1:0]    th_ok, adc_seen;
    reg  [THETA_LAT*NAXES-1:0] th_sr;   // the trigger delayed by 1..THETA_LAT clocks (the angle: at the last)
    wire [15:0]         lat_now;    // the job axis's clocks since its trigger, + 1 (at cmp_load: latency)
    reg  [PW*NAXES-1:0] pos_trig;
    wire [PW*NAXES-1:0] pos_hq;     // per axis: pos_{k-M} of the job's window (0 before M samples)
    wire [WFW-1:0]      j_win = (win_shift > WLF) ? WLF : win_shift;  // the job axis's m, 0..WL
    wire [WL:0]         j_wm  = {{WL{1'b0}}, 1'b1} << j_win;       // M = 2^m, 1..WD
    wire [WL-1:0]       j_tap = j_wm[WL-1:0] - {{(WL-1){1'b0}}, 1'b1};  // M - 1 (M = WD: WD - 1)
    reg  [AB*NAXES-1:0] th_trig;
    wire [NAXES-1:0]    busy_ax;    // a job of the axis waits or runs
    wire [NAXES-1:0]    trig;       // a trigger taken
    wire [8*NAXES-1:0]  per_cnt;    // (read by tb/hdl/cosim_top.v only)
    genvar ga;
    generate for (ga = 0; ga < NAXES; ga = ga + 1) begin : g_tim
        assign busy_ax[ga] = tpend[ga] || (busy_period && ax_oh[ga]);
        assign trig[ga] = adc_trig[ga] && !busy_ax[ga];
        // the coming sample is a control sample: the compare registered, so that ctl_boundary is one
        // gate from registers into the core's swap logic (18 LUT less in the drive).  One clock old:
        // per_nx changes at a trigger; a pwm_per_control write (bridges off only) in the clock before
        // a boundary takes effect at the next one, for ctl_next, the advance and the swap alike
        always @(posedge clk) ctl_now[ga] <= !rst && (per_nx[8*ga +: 8] >= pwm_per_control[8*ga +: 8]);
        assign ctl_boundary[ga] = period_start[ga] && ctl_now[ga];
        assign per_cnt[8*ga +: 8] = per_nx[8*ga +: 8] - 8'd1;
        // the counts of the last WD control samples (before this one): a shift register with a
        // dynamic tap (WD = 16: SRL16 per bit, 32 LUTs per axis, no reset: nh counts the samples shifted
        // in since rst, saturating at WD, and the tap reads 0 until it holds M of them, as the state
        // RAM's pos_prev after its clear).  Tap M - 1 = pos_{k-M}; the job's window m is the job
        // axis's KACC.win (win_shift), read only while the job runs (pos_trig / the history stay).
        // One WD-bit shift register per count bit, tap bit j_tap (yosys xilinx_srl -variable: SRLC16E).
        reg  [WL:0]   nh;
        wire          ph_sh = trig[ga] && ctl_next[ga];
        wire [PW-1:0] ph_q;
        genvar gb;
        for (gb = 0; gb < PW; gb = gb + 1) begin : g_ph
            reg [WD-1:0] sr;
            always @(posedge clk)
                if (ph_sh) sr <= {sr[WD-2:0], pos_trig[PW*ga + gb]};
            assign ph_q[gb] = sr[j_tap];
        end
        always @(posedge clk)
            if (rst) nh <= {(WL+1){1'b0}};
            else if (ph_sh && !nh[WL]) nh <= nh + {{WL{1'b0}}, 1'b1};
        assign pos_hq[PW*ga +: PW] = (nh >= j_wm) ? ph_q : {PW{1'b0}};
        always @(posedge clk) begin
            pos_sample[ga] <= 1'b0;
            ref_advance[ga] <= 1'b0;
            overrun[ga] <= 1'b0;
            if (rst) begin
                ctl_next[ga] <= 1'b0;
                first[ga] <= 1'b1;
                pos_trig[PW*ga +: PW] <= {PW{1'b0}};
                th_trig[AB*ga +: AB] <= {AB{1'b0}};
                th_ok[ga] <= 1'b0;
                adc_seen[ga] <= 1'b0;
            end else begin
                if (period_start[ga] && busy_ax[ga])
                    overrun[ga] <= 1'b1;
                // ---- boundary: the coming sample's kind; the references advance now ----
                if (period_start[ga]) begin
                    ctl_next[ga] <= ctl_now[ga];
                    ref_advance[ga] <= ctl_now[ga];
                end
                // ---- trigger: the count now, the angle THETA_LAT clocks later ----
                if (trig[ga]) begin
                    th_ok[ga] <= 1'b0;
                    adc_seen[ga] <= 1'b0;
                    if (ctl_next[ga]) begin
                        pos_sample[ga] <= 1'b1;
                        pos_trig[PW*ga +: PW] <= pos[PW*ga +: PW];
                    end
                end
                if (jst_oh[ga]) first[ga] <= 1'b0;
                if (th_sr[THETA_LAT*ga + THETA_LAT - 1]) begin
                    th_trig[AB*ga +: AB] <= theta[AB*ga +: AB];
                    th_ok[ga] <= 1'b1;
                end
                if (busy_ax[ga] && adc_valid[ga]) adc_seen[ga] <= 1'b1;
            end
        end
        always @(posedge clk) begin
            if (rst || (trig[ga] && ctl_next[ga]))
                per_nx[8*ga +: 8] <= 8'd1;
            else if (trig[ga])
                per_nx[8*ga +: 8] <= per_nx[8*ga +: 8] + 8'd1;
            // no trigger of the axis while it waits (it is busy until its cmp_load, after the angle)
            th_sr[THETA_LAT*ga +: THETA_LAT] <= rst ? {THETA_LAT{1'b0}} :
                ((th_sr[THETA_LAT*ga +: THETA_LAT] << 1) | {{(THETA_LAT-1){1'b0}}, trig[ga]});
        end
    end endgenerate
    // latency: NAXES = 1 a counter from the trigger; NAXES > 1 one free-running clock count and the
    // count at each axis's trigger (no adder per axis): cmp_load's count - the trigger's is the same
    // value, modulo 2^16 as the counter's
    generate if (NAXES == 1) begin : g_lat1
        reg [15:0] lat_cnt;
        always @(posedge clk) begin
            if (trig[0])
                lat_cnt <= 16'd1;
            else if (busy_ax[0])
                lat_cnt <= lat_cnt + 16'd1;
        end
        assign lat_now = lat_cnt;
    end else begin : g_latn
        reg [15:0] now;
        reg [16*NAXES-1:0] t_trig;
        integer li;
        always @(posedge clk) begin
            now <= rst ? 16'd0 : now + 16'd1;
            for (li = 0; li < NAXES; li = li + 1)
                if (trig[li]) t_trig[16*li +: 16] <= now;
        end
        assign lat_now = now - t_trig[16*ax +: 16];
    end endgenerate

    // ================================ job queue ================================
    // NAXES = 1: a trigger starts the job at once (the axis is busy until its cmp_load).  NAXES > 1:
    // a trigger that finds the engine busy (or another axis starting in its clock) waits in a FIFO
    // of axes; jobs start in sample order (simultaneous triggers: the lower axis first), the clock
    // the engine is free; the axis is latched (ax) for the whole job.
    generate if (NAXES == 1) begin : g_q1
        assign jstart = trig[0];
        assign jax = {AXB{1'b0}};
        always @(posedge clk) tpend <= 1'b0;
        assign ax_oh = 1'b1;
        assign job_next = 1'b1;
    end else begin : g_qn
        // each waiting axis holds its place in the sample order (q_seq, mod 4: at most NAXES wait);
        // the head is the waiting axis whose place is q_pop
        reg  [2*NAXES-1:0] q_seq, q_seq_n;
        reg  [1:0]         q_push, q_pop, np;
        reg  [NAXES-1:0]   push;
        reg                js;
        reg  [AXB-1:0]     ja;
        reg                idle0, lower;
        reg  [NAXES-1:0]   ax_ohr;      // one-hot of ax, registered with it (ax_oh: no decoder
                                        // between ax and busy_ax / trig, the queue's inputs)
        integer qi;
        // Timing (docs/blocks/mx_seq.md "Job queue timing"): with the engine idle and no trigger
        // waiting, busy_ax = 0, so trig = adc_trig there: the start decision and the lowest-axis
        // pick read adc_trig, not trig (same values), and push excludes the started axis by
        // "an adc_trig of a lower axis" instead of comparing ja; ax enters the queue only
        // through trig (one LUT: adc_trig, tpend, busy_period, ax_ohr)
        always @(*) begin
            idle0 = !busy_period && !(|tpend);
            js = 1'b0;
            ja = {AXB{1'b0}};
            if (!busy_period && |tpend) begin           // the oldest waiting trigger
                js = 1'b1;
                for (qi = 0; qi < NAXES; qi = qi + 1)
                    if (tpend[qi] && q_seq[2*qi +: 2] == q_pop) ja = qi[AXB-1:0];
            end else if (!busy_period) begin            // an idle engine: the lowest trigger now
                for (qi = NAXES - 1; qi >= 0; qi = qi - 1)
                    if (adc_trig[qi]) begin             // = trig[qi] here (nothing busy)
                        js = 1'b1;
                        ja = qi[AXB-1:0];
                    end
            end
            np = q_push;
            q_seq_n = q_seq;
            lower = 1'b0;                               // an adc_trig of a lower axis
            for (qi = 0; qi < NAXES; qi = qi + 1) begin
                // = trig[qi] && !(js && !(|tpend) && ja == qi): idle0 starts the lowest trigger
                push[qi] = trig[qi] && !(idle0 && !lower);
                lower = lower | adc_trig[qi];
                if (push[qi]) begin
                    q_seq_n[2*qi +: 2] = np;
                    np = np + 2'd1;
                end
            end
        end
        always @(posedge clk) begin
            if (rst) begin
                q_push <= 2'd0;
                q_pop <= 2'd0;
                tpend <= {NAXES{1'b0}};
            end else begin
                q_push <= np;
                if (js && |tpend) q_pop <= q_pop + 2'd1;
                tpend <= (tpend | push) & ~jst_oh;
            end
            q_seq <= q_seq_n;
            ax_ohr <= job_next;                                 // one-hot of ax's next value (below)
        end
        assign jstart = js;
        assign jax = ja;
        assign ax_oh = ax_ohr;
        // ax_ohr's D, as ax's update (rst: ax <= 0; js: ax <= jax); also for a parent's copies that load in
        // the clock before ax changes
        assign job_next = rst ? {{(NAXES-1){1'b0}}, 1'b1} : js ? ({{(NAXES-1){1'b0}}, 1'b1} << ja) : ax_ohr;
    end endgenerate
    assign jst_oh = {NAXES{jstart}} & ({{(NAXES-1){1'b0}}, 1'b1} << jax);

    // the job axis's inputs (NAXES = 1: the ports)
    wire [PW-1:0]  j_pos   = pos_trig[PW*ax +: PW];
    wire [PW-1:0]  j_ph    = pos_hq[PW*ax +: PW];
    wire [CUW-1:0] j_cur0  = cur0[CUW*ax +: CUW];
    wire [CUW-1:0] j_cur1  = cur1[CUW*ax +: CUW];
    wire [CUW-1:0] j_cur2  = cur2[CUW*ax +: CUW];
    assign job_axis = ax;           // the register block reads the job axis's registers at it
    wire [17:0]    j_kdc   = kdc;
    wire [17:0]    j_kacc  = kacc;
    wire [4:0]     j_ksh   = kacc_shift;
    wire [3:0]     j_lsh   = load_shift;
    wire [4:0]     j_lsm   = ({1'b0, j_lsh} + 5'd1 < {2'd0, j_win}) ? 5'd0 : {1'b0, j_lsh} + 5'd1 - {2'd0, j_win};
    wire [IW-1:0]  j_idr   = id_ref;
    wire [IW-1:0]  j_iqr   = iq_ref;
    wire           j_run   = run[ax];
    wire           j_adc   = adc_seen[ax];
    wire           j_thok  = th_ok[ax];
    wire           s_ctl   = ctl_next[jax];     // the starting job's kind and task
    wire           s_tpos  = task_pos[jax];
    assign theta_trig = th_trig[AB*ax +: AB];

    // transform chain (xform): front with theta_trig, mod with theta_mod and the held u
    reg  xf_front, xf_mod, xf_run_mod;
    wire xf_busy, xf_done, xf_sat;
    wire [CW-1:0] cmp_a, cmp_b, cmp_c;
    wire signed [35:0] pr;          // kacc * i_q on xform's multiplier, after the front
    reg  [AB-1:0] th_mod;
    wire [AB-1:0] ang = xf_front ? theta_trig : th_mod;
    wire signed [UW-1:0] u_st0, u_st1;      // the held u of the job's axis (0 while zeroed)
    xform u_xform (.clk(clk), .rst(rst), .start_front(xf_front), .start_mod(xf_mod), .angle(ang),
                   .i_a(j_cur0), .i_b(j_cur1), .i_c(j_cur2), .u_d(u_st0), .u_q(u_st1), .kdc(j_kdc), .mul_b(j_kacc),
                   .busy(xf_busy), .done(xf_done), .sat(xf_sat), .i_d(i_d), .i_q(i_q),
                   .cmp_a(cmp_a), .cmp_b(cmp_b), .cmp_c(cmp_c), .prod(pr));
    assign cmp = {cmp_c, cmp_b, cmp_a};

    // engine actions (W stage of the ALU, below)
    wire        a_start, a_mod, a_end, eng_sat;

    always @(posedge clk) begin
        xf_front <= 1'b0;
        xf_mod <= 1'b0;
        core_start <= {NAXES{1'b0}};
        cmp_load <= {NAXES{1'b0}};
        control_done <= {NAXES{1'b0}};
        front_sat <= {NAXES{1'b0}};
        stat_sweep <= {NAXES{1'b0}};
        if (rst) begin
            is_control <= 1'b0;
            mfirst <= 1'b1;
            busy_period <= 1'b0;
            latency <= {(16*NAXES){1'b0}};
            front_go <= 1'b0;
            front_done <= 1'b0;
            core_run <= 1'b0;
            core_fin <= 1'b0;
            xf_run_mod <= 1'b0;
            ax <= {AXB{1'b0}};
        end else begin
            // ---- job start ----
            if (jstart) begin
                ax <= jax;
                mfirst <= first[jax];
                busy_period <= 1'b1;
                is_control <= s_ctl;
                front_go <= 1'b0;
                front_done <= 1'b0;
                core_fin <= !s_ctl;             // a modulation-only period needs no core
            end
            // ---- ADC, front ----
            if (is_control && busy_period && j_adc && j_thok && !front_go && !xf_busy) begin
                xf_front <= 1'b1;
                front_go <= 1'b1;
            end
            if (xf_done && !xf_run_mod && is_control) begin
                front_done <= 1'b1;
                if (xf_sat) front_sat <= ax_oh;
            end
            if (eng_sat) front_sat <= ax_oh;
            // ---- core ----
            if (a_start) begin
                if (j_run) begin
                    core_start <= ax_oh;
                    core_run <= 1'b1;
                end else begin
                    core_fin <= 1'b1;
                    control_done <= ax_oh;
                end
            end
            if (core_run && core_done) begin
                core_run <= 1'b0;
                core_fin <= 1'b1;
                control_done <= ax_oh;
            end
            // ---- modulation ----
            if (a_mod) xf_mod <= 1'b1;
            if (xf_mod && !xf_busy) xf_run_mod <= 1'b1;
            if (xf_done && xf_run_mod) begin
                xf_run_mod <= 1'b0;
                if (xf_sat) front_sat <= ax_oh;
                cmp_load <= ax_oh;
                stat_sweep <= {NAXES{is_control}} & ax_oh;
                latency[16*ax +: 16] <= lat_now;
                busy_period <= 1'b0;
            end
        end
    end

    // held u and ebar of the axis: u loaded at core_done, both 0 while the law is off (zeroed: the
    // law was off since the axis's last core update).  NAXES = 1: u_st0/1 registers, ebar = the
    // core's outputs (they hold until its next update); NAXES > 1: a copy per axis, taken at core_done
    wire [NAXES-1:0] zeroed_nx;
    wire [3*SW-1:0]  ebar_h;        // the job axis's ebar(k-1)
    generate if (NAXES == 1) begin : g_hold1
        reg zeroed;
        reg signed [UW-1:0] u_h0, u_h1;
        always @(posedge clk) zeroed <= rst ? 1'b1 : core_done ? 1'b0 : (!run[0] ? 1'b1 : zeroed);
        always @(posedge clk) begin
            if (rst || (!run[0] && !core_done)) begin
                u_h0 <= {UW{1'b0}};
                u_h1 <= {UW{1'b0}};
            end else if (core_done) begin
                u_h0 <= core_u[0 +: UW];
                u_h1 <= core_u[UW +: UW];
            end
        end
        assign u_st0 = u_h0;
        assign u_st1 = u_h1;
        assign zeroed_nx = rst || (!core_done && (!run[0] || zeroed));
        assign ebar_h = core_ebar;
    end else begin : g_holdn
        reg  [NAXES-1:0] zeroed;
        // block RAM (4 RAMB8 of 36 bits, one word {ebar, u} per axis; 96 LUT as LUT RAM), read
        // registered at the job axis and cleared (the RAMs' output reset) while zeroed: hq is the word
        // of ax, 0 while zeroed[ax], from the second clock after its write or a job start (the program
        // reads u >= 2 clocks after core_done, u and ebar >= 6 after a job start, ebar never at a done)
        (* ram_style = "block" *) reg [2*UW+3*SW-1:0] hold [0:NAXES-1];
        reg  [2*UW+3*SW-1:0] hq;
        always @(posedge clk) begin
            if (core_done) hold[ax] <= {core_ebar, core_u};
            hq <= zeroed_nx[ax] ? {(2*UW+3*SW){1'b0}} : hold[ax];
        end
        integer zi;
        always @(posedge clk)
            for (zi = 0; zi < NAXES; zi = zi + 1)
                zeroed[zi] <= rst ? 1'b1 : (core_done && ax_oh[zi]) ? 1'b0 : (!run[zi] ? 1'b1 : zeroed[zi]);
        assign u_st0 = hq[0 +: UW];
        assign u_st1 = hq[UW +: UW];
        assign zeroed_nx = rst ? {NAXES{1'b1}} : ~(ax_oh & {NAXES{core_done}}) & (~run | zeroed);
        assign ebar_h = hq[2*UW +: 3*SW];
    end endgenerate

    // ===================================== engine =====================================
    (* rom_style = "block" *) reg [35:0] rom [0:255];
    integer ui;
    initial begin
`include "mx_seq_rom.vh"
    end
    reg  [7:0]  pc, pc_next;
    reg  [35:0] iw;                 // rom[pc] (block RAM output register)
    reg         prun;               // a program is running
    reg  [NAXES-1:0] refs_ok;       // per axis: its references are in the state RAM
    reg         refs_taken;
    reg         sh_busy;
    wire [2:0]  i_ctl = iw[UW_CTL +: 3];
    reg         cond_ok;
    always @(*) begin
        case (i_ctl)
            CTL_WTH:    cond_ok = j_thok;
            CTL_WREF:   cond_ok = refs_ok[ax];
            CTL_WFRONT: cond_ok = front_done;
            CTL_WSH:    cond_ok = !sh_busy;
            CTL_WCORE:  cond_ok = core_fin;
            default:    cond_ok = 1'b1;
        endcase
    end
    wire        issue = prun && cond_ok;
    always @(*) begin
        if (jstart) pc_next = !s_ctl ? PC_MOD : s_tpos ? PC_POS : PC_SPD;
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
            if (jstart) begin
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
    reg  [PW-1:0] g_pos;            // POS or PH (never both: one stage, no extra OR input)
    reg  [AB-1:0] g_th;
    reg  [IW-1:0] g_id, g_iq, g_idr, g_iqr;
    reg  [UW-1:0] g_u0, g_u1;
    reg  [SW-1:0] g_e0, g_e1, g_e2, g_om;
    reg  [SHW-1:0] g_sh;
    reg           g_p;
    reg  signed [SHW-1:0] sh;               // serial shifter
    always @(posedge clk) begin
        g_pos <= ((issue && i_as == AS_POS) ? j_pos : {PW{1'b0}}) | ((issue && i_as == AS_PH) ? j_ph : {PW{1'b0}});
        g_th  <= (issue && i_as == AS_TH)  ? theta_trig : {AB{1'b0}};
        g_id  <= (issue && i_as == AS_ID)  ? i_d : {IW{1'b0}};
        g_iq  <= (issue && i_as == AS_IQ)  ? i_q : {IW{1'b0}};
        g_idr <= (issue && i_as == AS_IDR) ? j_idr : {IW{1'b0}};
        g_iqr <= (issue && i_as == AS_IQR) ? j_iqr : {IW{1'b0}};
        g_u0  <= (issue && i_as == AS_U0)  ? u_st0 : {UW{1'b0}};
        g_u1  <= (issue && i_as == AS_U1)  ? u_st1 : {UW{1'b0}};
        g_e0  <= (issue && i_as == AS_E0 && !zeroed_nx[ax]) ? ebar_h[0*SW +: SW] : {SW{1'b0}};
        g_e1  <= (issue && i_as == AS_E1 && !zeroed_nx[ax]) ? ebar_h[1*SW +: SW] : {SW{1'b0}};
        g_e2  <= (issue && i_as == AS_E2 && !zeroed_nx[ax]) ? ebar_h[2*SW +: SW] : {SW{1'b0}};
        g_om  <= (issue && i_as == AS_OMR) ? omega : {SW{1'b0}};
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
                          {{(XW-SHW){g_sh[SHW-1]}}, g_sh} | p_fwd;
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
    wire [5+$clog2(NAXES):0] da_ax;     // {axis, word} of a core input / status write
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
            CD_LS:    w_ok_c = (j_lsh != 4'd0);
            CD_NOLS:  w_ok_c = (j_lsh == 4'd0);
            default:  w_ok_c = 1'b1;
        endcase
    end
    wire          wen = w_v && w_ok_c;
    // omega's D (the only place omega's update is written), also for a parent's per-axis copies (mx_axes:
    // each axis's speed for the reference sync)
    assign omega_next = rst ? {SW{1'b0}} : (wen && w_dk == DK_OMR) ? w32 : omega;
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
            core_in_addr <= da_ax;
            core_in_wdata <= w32;
            st_addr <= da_ax;
            st_wdata <= w32;
        end
        omega <= omega_next;
        if (wen && w_dk == DK_THM) th_mod <= w32[AB-1:0];
    end
    // serial shifter: loaded with R (SHKA: with kacc * i_q, xform's product, held since the front: no A stage for
    // it), then count steps of an arithmetic right shift (sh_r: the bit out): kacc_shift (SHKA), m (SHT2,
    // da[0] = 1: the speed window) or load_shift + 1 - m, at least 0 (SHT2, da[0] = 0: the load update)
    reg  [4:0]    sh_cnt;
    wire [4:0]    sh_n = (w_dk == DK_SHKA) ? j_ksh : w_da[0] ? {2'd0, j_win} : j_lsm;
    always @(posedge clk) begin
        if (wen && (w_dk == DK_SHKA || w_dk == DK_SHT2)) begin
            sh <= (w_dk == DK_SHKA) ? {{(SHW-36){pr[35]}}, pr} : r[SHW-1:0];
            sh_r <= 1'b0;
            sh_cnt <= sh_n;
            sh_busy <= (sh_n != 5'd0);
        end else if (sh_busy) begin
            sh <= sh >>> 1;
            sh_r <= sh[0];
            sh_cnt <= sh_cnt - 5'd1;
            sh_busy <= (sh_cnt != 5'd1);
        end
        if (rst) sh_busy <= 1'b0;
    end

    // ---------------- axis state RAM: port A (ALU W stage, reference prefetch, clear after rst) ----------------
    reg  [CLB-1:0] clr_cnt;             // 32 x NAXES words (NAXES = 1: 32)
    reg           clr;
    reg  [NAXES-1:0] pf_need;           // per axis: its references are to be read (after its advance)
    reg  [2*NAXES-1:0] pf_g;
    reg           pf_act;               // the prefetch engine reads the references of axis pf_ax
    reg  [AXB-1:0] pf_ax;
    reg  [PFB-1:0] pf_cnt;
    reg  [31:0]   pf_sr;
    wire          alu_ram = wen && w_dk == DK_RAM;
    // the prefetch pauses while the job of its axis takes the references (an overrun job)
    wire          pf_go = pf_act && !alu_ram && !clr && (!busy_period || !refs_taken || ax != pf_ax);
    wire [31:0]   pf_word = {ref_q, pf_sr[31:1]};
    wire          pf_wr = pf_go && (pf_cnt[4:0] == 5'd31);
    wire [4:0]    pf_wa = SW_REF0 + {pf_cnt[PFB-1:5]};
    wire [AW-1:0] pf_age = N[AW-1:0] - pf_cnt[PFB-1:6];
    assign ref_bit = pf_cnt[5:0];
    wire [AXB+4:0] clr_a;
    generate if (NAXES == 1) begin : g_a1
        assign ref_age = pf_age;
        assign da_ax = w_da;
        assign clr_a = {ax, clr_cnt[4:0]};
    end else begin : g_an
        assign ref_age = {pf_ax[$clog2(NAXES)-1:0], pf_age};
        assign da_ax = {ax[$clog2(NAXES)-1:0], w_da};
        assign clr_a = clr_cnt[AXB+4:0];
    end endgenerate
    always @(posedge clk) begin
        if (clr)
            sram[clr_a] <= {RW{1'b0}};
        else if (alu_ram)
            sram[{ax, w_da[4:0]}] <= w36;
        else if (pf_wr)
            sram[{pf_ax, pf_wa}] <= {{(RW-32){pf_word[31]}}, pf_word};
    end
    always @(posedge clk) begin
        if (rst) begin
            clr <= 1'b1;
            clr_cnt <= {CLB{1'b0}};
        end else if (clr) begin
            clr_cnt <= clr_cnt + 1'b1;
            if (clr_cnt == CLR_LAST[CLB-1:0]) clr <= 1'b0;
        end
    end
    // reference prefetch: after each advance of an axis (and after anything else that drops its
    // w_ok), read its w_k .. w_{k+N} into its RAM words; refs_ok while they are current.  One engine:
    // the lowest axis first among those ready (the advances of different axes are a stagger apart)
    wire [NAXES-1:0] pf_rst;            // the axis's references are (again) to be read
    wire          pf_done = pf_go && pf_cnt == NREF[PFB-1:0] - 1'b1 && !pf_rst[pf_ax];
    reg           pf_take;
    reg  [AXB-1:0] pf_sel;
    integer pi;
    always @(*) begin
        pf_take = 1'b0;
        pf_sel = {AXB{1'b0}};
        for (pi = NAXES - 1; pi >= 0; pi = pi - 1)
            if (!pf_act && pf_need[pi] && pf_g[2*pi +: 2] == 2'd0 && ref_ok[pi] && !pf_rst[pi]) begin
                pf_take = 1'b1;
                pf_sel = pi[AXB-1:0];
            end
    end
    generate for (ga = 0; ga < NAXES; ga = ga + 1) begin : g_pf
        assign pf_rst[ga] = rst || (period_start[ga] && ctl_now[ga]) ||
                            (!ref_ok[ga] && ((pf_act && pf_ax == ga) || refs_ok[ga]));
        always @(posedge clk) begin
            if (pf_rst[ga]) begin
                pf_need[ga] <= 1'b1;
                refs_ok[ga] <= 1'b0;
                pf_g[2*ga +: 2] <= 2'd3;    // ref_gen's w_ok falls 2 clocks after our advance strobe
            end else begin
                if (pf_g[2*ga +: 2] != 2'd0) pf_g[2*ga +: 2] <= pf_g[2*ga +: 2] - 2'd1;
                if (pf_take && pf_sel == ga) pf_need[ga] <= 1'b0;
                if (pf_done && pf_ax == ga) refs_ok[ga] <= 1'b1;
            end
        end
    end endgenerate
    always @(posedge clk) begin
        if (rst || (pf_act && pf_rst[pf_ax]) || pf_done)
            pf_act <= 1'b0;
        else if (pf_take) begin
            pf_act <= 1'b1;
            pf_ax <= pf_sel;
        end
        if (rst) pf_ax <= {AXB{1'b0}};
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
