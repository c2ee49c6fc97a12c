// ctrl_seq: per-axis control sequencer (paper 000 Fig. 3, sec. V-A), on a bit-serial datapath.
//
// Every PWM period, at the ADC trigger (period centre), it latches the encoder count
// and, THETA_LAT clocks later, the electrical angle theta_trig computed from that count
// (pos_sense needs THETA_LAT clocks from a count to its angle), and runs the
// modulation chain for the held u_dq when the ADC samples have arrived:
//   theta_mod = theta_trig + (theta_trig - theta_trig_prev)   (one PWM period ahead:
//               the angle in the middle of the period the new duties are applied)
//   xform mod: inv_park(u, theta_mod) -> inv_clarke -> min_sub -> duty_scale(kdc) -> cmp, cmp_load
// In the last PWM period of each control period (pwm_per_control periods), before
// the modulation it runs the control law:
//   xform front: clarke(i_abc) -> park(theta_trig) -> i_d, i_q
//   omega = sat32(spd + ka - D), spd = sat32((pos_trig - pos_prev) << 16) (eq. 37 in counts per
//           Ts), ka = rshift_round(kacc * i_q, kacc_shift) (the (Ts/2) acceleration term), D the
//           load estimate: D += (2 (ka - D) - (spd - spd_prev)) >>> (load_shift + 1) (0 if
//           load_shift = 0; 40 bit, never wraps: |D| < 2^35), docs/blocks/ctrl_seq.md
//   core inputs (raw units), written one word per clock into the core's input buffer:
//   y = (i_d, i_q, omega | 0), omega, dx = x_k - x_{k-1} (dx2 = omega - omega_prev and
//   dx3 = dpos << 8 saturated to SIG_W, front_sat), u_prev, ebar_prev, and the
//   references w_k..w_{k+N} read bit by bit from ref_gen (Q.32) -> Q16.16 speed or, for
//   the position task, Q32.8 relative to the measured count (modulo 2^32, so the
//   encoder wrap is harmless; the core's own translation then subtracts 0), rounded
//   half up and saturated to SIG_W
//   -> mpc_core start/done -> u, ebar (held by the core; u also here as u_st).
// With run = 0 the law is skipped and u = ebar = 0 (bridges, if enabled, see zero voltage).
// Bit-exact to gen/empc/rtlmodel/ctrl_seq.py (CtrlSeq.period) with mpc_core.py.
//
// Three parts: the period bookkeeping (trigger, theta, xform front / mod, core handshake,
// latency), the engine that forms the core's input words, and its interfaces.  The engine runs
// a microprogram (block RAM; generated with its pass table from the tables in
// gen/empc/rtlmodel/ctrl_seq.py): the control program from the trigger of a control period, a
// status program (U_D, U_Q) at every modulation start, and the sweeps of axis_status.  Its
// datapath is bit-serial (LSB first, one bit per clock; no multiplier, no wide adder):
//   X        40-bit word register, X[SIG_W-1:0] = the core's in_wdata.  A word to copy (i_d, i_q,
//            id_ref, iq_ref, u_prev, ebar_prev, the count) is loaded in parallel as the OR
//            of "stage" registers, each a copy of its source that is held at 0 (flip-flop
//            reset) except in the one clock it is selected; a computed word is shifted in
//            at the top while the operand leaves at the bottom (X[0]).
//   ALU      one serial adder A + (B or ~B) + carry (0..2: subtract with rounding), sign
//            extension of narrow operands by holding their top bit, overflow flags and a
//            saturation pattern for the words that saturate (omega; references, dx2, dx3 to
//            SIG_W: a word whose 40-bit result does not fit is rewritten in X, state E_FIX).
//   rings    shift registers holding the previous i_d, i_q, omega, count (B operands,
//            refilled from the A stream in the same pass), dpos, omega (result), the
//            acceleration term ka; none needs a data multiplexer.
//   mult     kacc * i_q: a serial-parallel multiplier (19-bit adder) fed with i_q bit by
//            bit; its product stream is shifted through a 41-bit register for s + 40
//            steps (s = kacc_shift), which leaves ka = product >> s in bits 40:1 and the
//            rounding bit product[s-1] in bit 0 (0 for s = 0).
//   load     the speed estimate's load term: rings ldd (D, 40 bit), spp (spd of the previous
//            control period, 32) and ldt (t2, 40); the OM pass forms u1 = ka - D (own subtractor,
//            carry-in 1 + rounding bit), omega = spd + u1 and t2 = 2 u1 - spd + spd_prev (two
//            more 1-bit adders) and refills spp; the LD pass D += t2 >>> (load_shift + 1) (a
//            tap of ldt, which shifts arithmetically).
// The theta unit has its own 1-bit adder: theta_mod = 2 theta_trig - theta_prev (theta_trig if
// first), written into the xform angle register after the front has started.
//
// Ports: see below; formats are those of empc_formats.vh.  References: ref_ok (ref_gen
// w_ok), ref_age / ref_bit -> ref_q (combinational).  Status (axis_status): the words I_D,
// I_Q, SPEED, REF (w_k in the task window: bits 47:16 speed, 55:24 position), U_D, U_Q leave
// bit-serially (st_*) while they pass through the datapath; the sweeps (sw_*, ctl_go) are
// programs of this engine whose word bits axis_status supplies.  core_in_* and st_*, sw_go,
// sw_end, ctl_go are combinational from this module's registers (ctl_go and sw_go also from
// adc_trig / sw_req).
// Latency: adc_trig -> cmp_load is reported on `latency` (clocks) every period; it must
// end before the next period boundary (PWM_HALF_PERIOD clocks after the trigger), else
// `overrun` pulses at the boundary (a trigger while a period is still running is ignored).
// Modulation period: ADC conversion + 84 (xform mod) + 3 clocks (155 in the co-simulation);
// control period: 693 (position task) / 728 (speed task) clocks in the co-simulations for
// N = 4, +40 per saturated word (E_FIX) and any ref_ok wait, then the counter sweep (about
// 500 clocks, after cmp_load; see docs/blocks/ctrl_seq.md).
// Reset: idle, u = 0, previous-sample registers 0, first-period flag set.
`default_nettype none
`include "empc_formats.vh"
`include "empc_regs.vh"
module ctrl_seq #(
    parameter integer N = `EMPC_N,
    parameter integer CW = $clog2(`EMPC_PWM_HALF_PERIOD + 1),
    parameter integer THETA_LAT = 4,    // pos_sense: clocks from a count to its angle (1..8)
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
    input  wire [`EMPC_ANGLE_BITS-1:0]    theta,           // pos_sense, continuous
    input  wire [`EMPC_POS_W-1:0]         pos,             // encoder count
    output reg                            pos_sample,      // -> pos_sense.sample (status only)
    input  wire                           adc_valid,
    input  wire signed [`EMPC_ADC_BITS:0] cur0,
    input  wire signed [`EMPC_ADC_BITS:0] cur1,
    input  wire signed [`EMPC_ADC_BITS:0] cur2,
    // registers
    input  wire [17:0]                    kdc,
    input  wire signed [17:0]             kacc,
    input  wire [4:0]                     kacc_shift,
    input  wire [3:0]                     load_shift,      // KACC.load_shift (0: no load estimate)
    input  wire signed [`EMPC_I_W-1:0]    id_ref,
    input  wire signed [`EMPC_I_W-1:0]    iq_ref,
    input  wire                           task_pos,        // active coefficient bank: position task
    // reference generator
    output reg                            ref_advance,
    input  wire                           ref_ok,          // w_k .. w_{k+N} current
    output wire [AW-1:0]                  ref_age,         // N - m for w_{k+m}
    output wire [5:0]                     ref_bit,
    input  wire                           ref_q,
    // MPC core
    output reg                            core_start,
    output wire                           core_in_we,      // input buffer (map: EMPC_IN_* / mpc_core.py)
    output wire [5:0]                     core_in_addr,
    output wire signed [`EMPC_SIG_W-1:0]  core_in_wdata,
    input  wire                           core_done,
    input  wire [2*`EMPC_U_W-1:0]         core_u,
    input  wire [3*`EMPC_SIG_W-1:0]       core_ebar,
    // PWM
    output wire [3*CW-1:0]                cmp,
    output reg                            cmp_load,
    // status
    output reg                            control_done,    // pulse: a control period completed
    output reg                            overrun,         // pulse: computation missed the boundary
    output reg                            front_sat,       // pulse: a front-end block saturated
    output reg  [15:0]                    latency,
    output wire signed [`EMPC_I_W-1:0]    i_d,
    output wire signed [`EMPC_I_W-1:0]    i_q,
    output reg  signed [`EMPC_W_W-1:0]    omega,
    output reg  [`EMPC_ANGLE_BITS-1:0]    theta_trig,
    // status words and counters (axis_status): a word streams bit-serially (LSB first), st_d
    // shifted in with st_sh, then written to register offset st_addr with st_wr; st_bit = the
    // bit of word st_addr that st_sh takes next clock
    output wire                           st_sh,
    output wire                           st_d,
    output wire                           st_wr,
    output wire [5:0]                     st_addr,
    output wire [4:0]                     st_bit,
    // sweeps: axis_status asks for one (sw_req; sw_all: the zero sweep after rst, status words
    // too), the engine runs it when idle (sw_go .. sw_end; its word bits come from axis_status);
    // ctl_go, the start of a control period, interrupts it
    input  wire                           sw_req,
    input  wire                           sw_all,
    output wire                           sw_go,
    output wire                           sw_end,
    output wire                           ctl_go
);
    localparam integer SW = `EMPC_SIG_W;     // 32: core input words (X[SW-1:0])
    localparam integer XW = 40;              // X: the passes form 40-bit words, saturated to SW
    localparam integer UW = `EMPC_U_W;       // 24
    localparam integer IW = `EMPC_I_W;       // 18
    localparam integer WW = `EMPC_W_W;       // 32
    localparam integer AB = `EMPC_ANGLE_BITS; // 16
    localparam integer PW = `EMPC_POS_W;     // 32
    // microword fields, codes and entry points (generated from gen/empc/rtlmodel/ctrl_seq.py)
`include "ctrl_seq_ucode.vh"

    generate if (SW != 32 || UW != 24 || IW != 18 || WW != 32 || PW != 32 || AB != 16 ||
                 `EMPC_W_FRAC != 16 || `EMPC_TH_FRAC != 8 || N > 8 || THETA_LAT < 1 || THETA_LAT > 8 ||
                 `EMPC_IN_Y != 0 || `EMPC_IN_OMEGA != 3 || `EMPC_IN_DX != 4 || !UC_MAP_OK)
    begin : g_bad_params
        ctrl_seq_unsupported_parameters u_error ();   // no such module: elaboration stops here
    end endgenerate

    // ================================ period bookkeeping ================================
    reg  [7:0]  per_nx;             // PWM periods since the last control period, + 1 (mod 256):
                                    // held incremented so that the compare needs no adder in front
    reg         is_control;
    reg         first, mfirst;
    reg  [15:0] lat_cnt;
    reg         busy_period;        // between the trigger and cmp_load
    reg  [PW-1:0] pos_trig;
    reg  signed [UW-1:0] u_st0, u_st1;
    reg         zeroed;             // run was low since the last core update: u_prev = ebar_prev = 0
    reg         prog_done, front_done, adc_seen, core_run, core_fin;
    wire        trig = adc_trig && !busy_period;
    wire        ctl_now = (per_nx >= pwm_per_control);
    wire        go_ctl = trig && ctl_now;
    wire [7:0]  per_cnt = per_nx - 8'd1;    // (read by tb/hdl/cosim_top.v only: no logic in synthesis)
    wire        prog_end, eng_sat;          // engine: control program done, a dx / omega saturated

    // transform chain: one microprogrammed MAC (xform)
    reg  xf_front, xf_mod;
    wire xf_busy, xf_done, xf_sat;
    wire [CW-1:0] cmp_a, cmp_b, cmp_c;
    reg  [AB-1:0] ang;              // angle register: theta_trig for front, theta_mod for mod
    reg  xf_run_mod;                // the xform operation in flight is the modulation
    xform u_xform (.clk(clk), .rst(rst), .start_front(xf_front), .start_mod(xf_mod), .angle(ang),
                   .i_a(cur0), .i_b(cur1), .i_c(cur2), .u_d(u_st0), .u_q(u_st1), .kdc(kdc),
                   .busy(xf_busy), .done(xf_done), .sat(xf_sat), .i_d(i_d), .i_q(i_q),
                   .cmp_a(cmp_a), .cmp_b(cmp_b), .cmp_c(cmp_c));
    assign cmp = {cmp_c, cmp_b, cmp_a};

    // theta unit (own 1-bit adder)
    reg         th_wait_run, th_run, th_done, ang_run, ang_done;
    reg  [3:0]  jt;                 // theta wait (16 - THETA_LAT .. 15), then bit of the pass
    reg  [AB-1:0] tp, tm;           // theta_prev, theta_mod (shift registers)
    reg         ta_d, tc;           // theta bit jt-1 (2 theta), carry
    wire        ta  = theta_trig[jt];
    wire        tb  = mfirst ? ta : tp[0];
    wire        tr  = ta_d ^ ~tb ^ tc;          // 2 theta - theta_prev (theta if first)

    always @(posedge clk) begin
        // default single-cycle pulses
        xf_front <= 1'b0;
        xf_mod <= 1'b0;
        core_start <= 1'b0;
        cmp_load <= 1'b0;
        pos_sample <= 1'b0;
        ref_advance <= 1'b0;
        control_done <= 1'b0;
        overrun <= 1'b0;
        front_sat <= 1'b0;
        if (rst) begin
            is_control <= 1'b0;
            first <= 1'b1;
            mfirst <= 1'b1;
            busy_period <= 1'b0;
            latency <= 16'd0;
            pos_trig <= {PW{1'b0}};
            theta_trig <= {AB{1'b0}};
            zeroed <= 1'b1;
            th_wait_run <= 1'b0;
            th_run <= 1'b0;
            th_done <= 1'b0;
            ang_run <= 1'b0;
            ang_done <= 1'b0;
            prog_done <= 1'b0;
            front_done <= 1'b0;
            adc_seen <= 1'b0;
            core_run <= 1'b0;
            core_fin <= 1'b0;
        end else begin
            if (period_start && busy_period)
                overrun <= 1'b1;
            zeroed <= core_done ? 1'b0 : (!run ? 1'b1 : zeroed);

            // ---- trigger ----
            if (trig) begin
                mfirst <= first;
                first <= 1'b0;
                busy_period <= 1'b1;
                th_wait_run <= 1'b1;
                th_done <= 1'b0;
                ang_done <= 1'b0;
                adc_seen <= 1'b0;
                front_done <= 1'b0;
                prog_done <= 1'b0;
                core_fin <= 1'b0;
                if (ctl_now) begin
                    is_control <= 1'b1;
                    pos_sample <= 1'b1;
                    ref_advance <= 1'b1;
                    pos_trig <= pos;
                end else begin
                    is_control <= 1'b0;
                end
            end

            // ---- theta: latch (THETA_LAT clocks after the count), theta_mod pass, angle register ----
            if (th_wait_run || th_run || ang_run) begin        // (jt wraps from 15 to 0)
                if (th_wait_run && jt == 4'd15) begin
                    theta_trig <= theta;
                    th_wait_run <= 1'b0;
                    th_run <= 1'b1;
                end
                if (!th_wait_run && jt == 4'd15) begin
                    th_run <= 1'b0;
                    ang_run <= 1'b0;
                    th_done <= th_done | th_run;
                    ang_done <= ang_done | ang_run;
                end
            end
            // theta_mod into the angle register once the front (if any) has sampled theta_trig
            if (th_done && !ang_done && !ang_run && (!is_control || front_done || xf_busy))
                ang_run <= 1'b1;                                  // (jt is 0 after the theta pass)

            // ---- ADC, front ----
            if (busy_period && adc_valid) adc_seen <= 1'b1;
            if (is_control && busy_period && adc_seen && th_done && !ang_run && !ang_done &&
                !xf_busy && !xf_front && !front_done)
                xf_front <= 1'b1;
            if (xf_done && !xf_run_mod && is_control) begin
                front_done <= 1'b1;
                if (xf_sat) front_sat <= 1'b1;
            end
            if (eng_sat) front_sat <= 1'b1;

            // ---- core ----
            if (prog_end) prog_done <= 1'b1;
            if (prog_done && !core_fin && !core_run) begin
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
            if (busy_period && ang_done && adc_seen && !xf_busy && !xf_mod && !xf_front && !xf_run_mod &&
                (!is_control || core_fin))
                xf_mod <= 1'b1;
            if (xf_done && xf_run_mod) begin
                if (xf_sat) front_sat <= 1'b1;
                cmp_load <= 1'b1;
                latency <= lat_cnt + 16'd1;
                busy_period <= 1'b0;
            end
        end
    end

    // period count: its own block, so that the restart is the flip-flops' set/reset and the
    // trigger their enable (no multiplexer in front of the incrementer)
    always @(posedge clk) begin
        if (rst || go_ctl)
            per_nx <= 8'd1;
        else if (trig)
            per_nx <= per_nx + 8'd1;
    end

    // latency and theta counters: restarted by the trigger (flip-flop set/reset), counting as
    // enable.  Not reset by rst: both are restarted by the trigger before they are read, and
    // they never count when the trigger comes (busy_period low: no theta pass in flight)
    always @(posedge clk) begin
        if (trig)
            lat_cnt <= 16'd0;
        else if (busy_period)
            lat_cnt <= lat_cnt + 16'd1;
        if (trig)
            jt <= 4'd0 - THETA_LAT[3:0];
        else if (th_wait_run || th_run || ang_run)
            jt <= jt + 4'd1;
    end

    // theta_mod pass and the angle register
    always @(posedge clk) begin
        if (th_run) begin
            ta_d <= ta;
            tc <= (ta_d & ~tb) | (tc & (ta_d ^ ~tb));
            tm <= {tr, tm[AB-1:1]};
            tp <= {ta, tp[AB-1:1]};
            ang <= {ta, ang[AB-1:1]};
        end else begin
            ta_d <= 1'b0;
            tc <= 1'b1;
        end
        if (ang_run) begin
            ang <= {tm[0], ang[AB-1:1]};
            tm <= {tm[0], tm[AB-1:1]};
        end
        if (rst) begin
            tp <= {AB{1'b0}};
            ang <= {AB{1'b0}};
        end
    end

    // held u: loaded at core_done, 0 while run is low (flip-flop reset and enable, no mux)
    always @(posedge clk) begin
        if (rst || (!run && !core_done)) begin
            u_st0 <= {UW{1'b0}};
            u_st1 <= {UW{1'b0}};
        end else if (core_done) begin
            u_st0 <= core_u[0 +: UW];
            u_st1 <= core_u[UW +: UW];
        end
    end
    always @(posedge clk) begin
        if (rst) xf_run_mod <= 1'b0;
        else if (xf_mod && !xf_busy) xf_run_mod <= 1'b1;
        else if (xf_done && xf_run_mod) xf_run_mod <= 1'b0;
    end

    // ===================================== engine =====================================
    // The microprogram urom holds two 36-bit words per step: uw (the fields and the op flags)
    // at pc and ub (the engine's decode: stage selects, next-state classes of E_OP, zero writes,
    // end markers, pass-end actions) at 128 + pc, one image per horizon N; the pass table crom
    // one 18-bit word per (pass kind, bit j): which registers shift, when the pass ends, sign
    // holds, flag strobes.  Both images come from gen/empc/rtlmodel/ctrl_seq.py.
    localparam integer NSRC = UB_TO_STG - UB_NSEL;          // stage sources SRC_POS .. SRC_IQ (ub.nsel)
    (* rom_style = "block" *) reg [17:0] crom [0:1023];     // pass table (kinds 0..11, 64 bits each)
    (* rom_style = "block" *) reg [35:0] urom [0:255];      // microprogram: uw at pc, ub at 128 + pc
    integer ui;
    initial begin
`include "ctrl_seq_rom.vh"
    end
    reg  [6:0]  pc;
    reg  [6:0]  pc_next;
    reg  [35:0] uw, ub;             // urom[pc], urom[128 + pc]
    wire [5:0]  u_wa  = uw[UW_WA +: 6];

    // engine states
    localparam [2:0] E_IDLE = 3'd0, E_OP = 3'd1, E_STG = 3'd2, E_LD = 3'd3, E_PASS = 3'd4,
                     E_FIX = 3'd5, E_WR = 3'd6, E_WR2 = 3'd7;
    reg  [2:0]  est;
    reg  [5:0]  j;                  // bit of the pass

    // The op flags of uw, registered: uw comes out of block RAM (about 2 ns clock-to-out), and
    // decoding it in front of the serial ALU made the pass datapath 9 LUT levels deep (93.5 MHz
    // proxy).  uw changes only together with pc, which always enters E_OP for at least one clock,
    // so the registered flags are valid from the clock after E_OP on: in every state where the
    // pass datapath acts.  What acts in E_OP itself (next state, pass table and status
    // addresses, ALU carry preset, zero writes) uses the unregistered op_* bits.
    wire op_pos  = uw[UW_POS];
    wire op_ref  = uw[UW_REF];
    wire op_diff = uw[UW_DIFF];
    wire op_om   = uw[UW_OM];
    wire op_fix3 = uw[UW_FIX3];
    wire op_w6   = uw[UW_W6];
    wire op_stat = uw[UW_STAT];
    wire op_sub  = uw[UW_SUB] || (op_ref && task_pos);     // the pass subtracts B
    reg  is_pos, is_ref, is_diff, is_om, is_fix3, is_w6, is_stat, diff_q, sub, is_sat, is_back, is_stw, is_ld;
    always @(posedge clk) begin
        {is_pos, is_ref, is_diff, is_om, is_fix3, is_w6, is_stat} <=
            {op_pos, op_ref, op_diff, op_om, op_fix3, op_w6, op_stat};
        diff_q  <= uw[UW_SRC];      // SRC_IQ (9) vs SRC_ID (8)
        sub     <= op_sub;
        is_sat  <= ub[UB_SAT];      // result saturated to SW bits (POS, REF, W6)
        is_back <= ub[UB_BACK];     // back to E_OP at the pass end (OM, STAT, CNT)
        is_stw  <= ub[UB_STW];      // writes a status word at the pass end
        is_ld   <= ub[UB_LD];       // the load-estimate pass
    end
    wire in_pass = (est == E_PASS);

    // ---------------- stage registers and X ----------------
    // Each stage register holds its source in the clock after its select and is 0 otherwise
    // (the select drives the flip-flops' reset); X loads the OR of all stages.
    reg  [XW-1:0] x;
    reg  [PW-1:0] g_pos;
    reg  [IW-1:0] g_id, g_iq, g_idr, g_iqr;
    reg  [SW-1:0] g_e0, g_e1, g_e2;
    reg  [UW-1:0] g_u0, g_u1;
    // The selects are registered in the E_OP clock that enters E_STG (the step word ub cannot
    // change before E_LD), active low so that they drive the stage flip-flops' reset directly;
    // ebar_prev is selected unless zeroed is set in the E_STG clock (zeroed's next value).
    reg  [NSRC-1:0] nsel;
    wire          to_stg = !rst && (est == E_OP) && !go_ctl && (ub[UB_TO_STG] || (op_diff && front_done));
    wire          zeroed_nx = rst || (!core_done && (!run || zeroed));
    always @(posedge clk) begin
        nsel <= to_stg ? ub[UB_NSEL +: NSRC] : {NSRC{1'b1}};
        if (zeroed_nx) nsel[SRC_E2:SRC_E0] <= 3'b111;
    end
    always @(posedge clk) begin
        g_pos <= nsel[SRC_POS] ? {PW{1'b0}} : pos_trig;
        g_id  <= nsel[SRC_ID]  ? {IW{1'b0}} : i_d;
        g_iq  <= nsel[SRC_IQ]  ? {IW{1'b0}} : i_q;
        g_idr <= nsel[SRC_IDR] ? {IW{1'b0}} : id_ref;
        g_iqr <= nsel[SRC_IQR] ? {IW{1'b0}} : iq_ref;
        g_e0  <= nsel[SRC_E0]  ? {SW{1'b0}} : core_ebar[0*SW +: SW];
        g_e1  <= nsel[SRC_E1]  ? {SW{1'b0}} : core_ebar[1*SW +: SW];
        g_e2  <= nsel[SRC_E2]  ? {SW{1'b0}} : core_ebar[2*SW +: SW];
        g_u0  <= nsel[SRC_U0]  ? {UW{1'b0}} : u_st0;
        g_u1  <= nsel[SRC_U1]  ? {UW{1'b0}} : u_st1;
    end
    // sign of the staged 18-bit source / of any 18- or 24-bit source (unselected stages are 0)
    wire          g_s18 = g_id[IW-1] | g_iq[IW-1] | g_idr[IW-1] | g_iqr[IW-1];
    wire          g_s24 = g_s18 | g_u0[UW-1] | g_u1[UW-1];
    // the OR of the stages, sign-extended through the two registered sign bits; bits
    // 17:0 have 11 inputs with X's own shift: split 6 + 5 so that each is one LUT6
    (* keep *) wire [IW-1:0] g_lo = x[IW:1] | g_pos[IW-1:0] | g_e0[IW-1:0] | g_e1[IW-1:0] | g_e2[IW-1:0] |
                                    g_u0[IW-1:0];
    // (bits SW..XW-1 of a copied word are never written to the core: left 0 / unextended)
    wire [XW-1:0] g_all = {{(XW-PW){1'b0}}, g_pos[PW-1:IW], {IW{1'b0}}} |
                          {{(XW-SW){1'b0}}, g_e0[SW-1:IW] | g_e1[SW-1:IW] | g_e2[SW-1:IW], {IW{1'b0}}} |
                          {{(XW-SW){1'b0}}, {(SW-UW){g_s24}}, {(UW-IW){g_s18}}, g_id | g_iq | g_idr | g_iqr} |
                          {{(XW-UW){1'b0}}, g_u0[UW-1:IW], {IW{1'b0}}} | {{(XW-IW){1'b0}}, g_u1[IW-1:0] | g_lo} |
                          {{(XW-UW){1'b0}}, g_u1[UW-1:IW], {IW{1'b0}}};

    // ---------------- serial operands and ALU ----------------
    reg  [IW-1:0] idp, iqp;         // previous i_d, i_q
    reg  [WW-1:0] omp;              // previous omega
    reg  [PW-1:0] pp;               // previous count (after the POS pass: this period's count)
    reg  [PW-1:0] dp;               // dpos
    reg  [WW-1:0] om;               // omega (OM pass result, saturated by the FIX3 pass)
    reg  [40:0]   ka;               // product stream: ka = ka[40:1], rounding bit ka[0]
    reg           a_h, b_h;         // held sign bits
    reg           c0, c1;           // carry 0..2
    reg           sd, spd_ovf, om_ovf, om_sgn, rnd, nz;
    reg           w_trk, w_r, w_ovf, fix_sgn;   // SW-bit saturation of the word in X (from bit G)
    reg  [17:0]   pw;               // pass control word of (pass kind, j)
    reg  [17:0]   pwf;              // E_FIX table word of j (kind PK_FIX, second port of the pass table)
    // load estimate of the speed: D (ldd), spd_prev (spp), t2 (ldt); see the header
    reg  [39:0]   ldd, ldt;
    reg  [WW-1:0] spp;
    reg           cu0, cu1;         // u1 = ka - D: carry-in 1 + rounding bit (0..2, as c0 / c1)
    reg           u1d, cs1, cs2;    // u1 of the previous bit (2 u1), carries of t2 = 2 u1 - spd + spp
    reg           sph, cl;          // spp sign above bit 31, carry of the LD pass
    wire          u1b  = ka[1] ^ ~ldd[0] ^ cu0;
    wire          u1m  = (ka[1] & ~ldd[0]) | (cu0 & (ka[1] ^ ~ldd[0]));
    wire          sppb = (j > 6'd31) ? sph : spp[0];

    // reference pass: first bit j0 = the rounding bit (the REF window of w_k lies above it)
    wire [5:0] ref_j0  = task_pos ? 6'd23 : 6'd15;
    wire       p_xs  = pw[PT_XS], p_pe = pw[PT_PE], p_ss = pw[PT_SS], p_ha = pw[PT_HA], p_hb = pw[PT_HB];
    wire       p_ca  = pw[PT_CA], p_cb = pw[PT_CB], p_r1 = pw[PT_R1], p_r2 = pw[PT_R2], p_r3 = pw[PT_R3];
    wire       p_al  = pw[PT_AL], p_l31 = pw[PT_L31], p_l16 = pw[PT_L16], p_f1 = pw[PT_F1], p_f2 = pw[PT_F2];
    wire       p_f3  = pw[PT_F3], p_w0 = pw[PT_W0];

    // A operand
    wire spd_raw = spd_ovf ? (p_l31 ? ~sd : sd) : p_l16 ? 1'b0 : dp[0];
    reg  a_raw;
    always @(*) begin
        if (is_ref) a_raw = ref_q;
        else if (is_om) a_raw = spd_raw;
        else if (is_fix3) a_raw = om_ovf ? (p_l31 ? ~om_sgn : om_sgn) : om[0];
        else if (is_w6) a_raw = om[0];
        else a_raw = x[0];
    end
    wire a_bit  = p_ha ? a_h : a_raw;
    // B operand
    reg  b_raw;
    always @(*) begin
        if (is_pos) b_raw = pp[0];
        else if (is_ref) b_raw = p_r1 && pp[0];
        else if (is_diff) b_raw = diff_q ? iqp[0] : idp[0];
        else if (is_om) b_raw = u1b;
        else if (is_w6) b_raw = omp[0];
        else b_raw = 1'b0;
    end
    wire       b_bit  = p_hb ? b_h : b_raw;
    wire       s1b    = u1d ^ ~a_bit ^ cs1;
    wire       t2b    = s1b ^ sppb ^ cs2;
    wire       ltap   = ldt[{2'b00, load_shift} + 6'd1];          // bit j + load_shift + 1 of t2
    wire       ldb    = (load_shift != 4'd0) && (ldd[0] ^ ltap ^ cl);
    wire       b_eff  = b_bit ^ sub;
    wire       r      = a_bit ^ b_eff ^ c0;
    wire       maj    = (a_bit & b_eff) | (c0 & (a_bit ^ b_eff));
    wire       fix_end = (est == E_FIX) && pwf[PT_PE];
    wire       r_fix  = pwf[PT_XS] ? fix_sgn : ~fix_sgn;       // X = satSW pattern, sign-extended

    // pass control (status words and sweep words: 32 bits, written one clock after the last)
    wire       pass_end  = in_pass && p_pe;
    // the word formed in X does not fit SW bits: result bits SW-1 .. XW-1 (pass bits G .. end) not
    // all equal, including this clock's bit (used at the pass end); its sign: the computed top bit,
    // the reference sign for a speed reference (w[63]), and + for the one position-reference
    // wrap (rel + 2^23 carried into bit 63: rnd, bits 24..62 zero)
    wire       ovf_now = w_ovf || (w_trk && (r != w_r));
    wire       sgn_now = (is_ref && !task_pos) ? a_raw : (r && !(is_ref && rnd && !nz));
    wire       x_shift = (in_pass && p_xs) || (est == E_FIX);
    wire       x_in    = (est == E_FIX) ? r_fix : r;
    wire       x_load  = (est == E_LD);
    wire       x_clr   = (est == E_WR && !(is_fix3 && !task_pos)) || (est == E_WR2) ||
                         (pass_end && ((is_sat && ovf_now) || is_stat));
    wire       wr_zero = (est == E_OP) && (ub[UB_WZ] || (ub[UB_ZPOS] && task_pos));

    // ---------------- multiplier kacc * i_q (serial-parallel, steps mk = 0 .. s + 39) ----------------
    reg         mrun, msg;
    reg  [6:0]  mk;
    reg  signed [18:0] ms;
    // steps: mk = -39 .. s (7-bit two's complement); the first 18 take i_q bit j of the W5
    // pass (A), the rest its sign msg (captured at bit 17)
    wire        mb   = (in_pass && is_diff && p_r1) ? x[0] : msg;   // (A of the W5 pass is x[0])
    wire signed [18:0] msum = ms + (mb ? {kacc[17], kacc} : 19'sd0);
    wire        m_end = (mk[6:5] == 2'b00) && (mk[4:0] == kacc_shift);
    wire        m_start = (est == E_LD) && is_diff && diff_q;

    // ---------------- sequence ----------------
    // program entries: control (trigger of a control period), status (every modulation start),
    // a sweep of axis_status when nothing else runs (the zero sweep runs into the counter sweep)
    wire go_stat = xf_mod && !xf_busy && (est == E_IDLE);
    wire quiet   = (est == E_IDLE) && !busy_period && !xf_mod && !trig;
    wire go_sw   = quiet && sw_req;
    wire step    = (est == E_OP && ub[UB_ZERO]) ||
                   (est == E_WR && !(is_fix3 && !task_pos)) || (est == E_WR2) ||
                   (pass_end && is_back);
    always @(*) begin
        if (go_ctl) pc_next = PC_CTL;
        else if (go_stat) pc_next = PC_STAT;
        else if (go_sw) pc_next = sw_all ? PC_ZERO : PC_CNT;
        else if (step) pc_next = pc + 7'd1;
        else pc_next = pc;
    end
    reg  [5:0]  j_nx;
    wire [3:0]  pk = {uw[UW_PK + 3], uw[UW_PK + 2], uw[UW_PK + 1] | (op_ref & task_pos), uw[UW_PK]};
    always @(*) begin
        j_nx = j;
        if (est == E_OP) j_nx = op_ref ? ref_j0 : 6'd0;
        else if (in_pass) j_nx = pass_end ? 6'd0 : j + 6'd1;
        else if (est == E_FIX) j_nx = fix_end ? 6'd0 : j + 6'd1;
    end
    always @(posedge clk) begin
        uw <= urom[{1'b0, pc_next}];
        ub <= urom[{1'b1, pc_next}];
        pw <= crom[{pk, j_nx}];
        pwf <= crom[{PK_FIX, j_nx}];
    end
    assign prog_end = (est == E_OP) && ub[UB_END];
    // dx2 / dx3 saturated (E_FIX; not the references), omega saturated (FIX3): model front_sat
    assign eng_sat = (est == E_OP && op_fix3 && (spd_ovf || om_ovf)) ||
                     (pass_end && !is_back && is_sat && ovf_now && !is_ref);

    always @(posedge clk) begin
        if (rst) begin
            pc <= 7'd0;
            est <= E_IDLE;
            j <= 6'd0;
            omega <= {WW{1'b0}};
            mrun <= 1'b0;
        end else begin
            pc <= pc_next;
            j <= j_nx;
            case (est)
                E_IDLE: ;
                E_OP: begin
                    // POS, COPY, STAT; DIFF when the front is done / REF when the references are
                    // current, OM when the product is ready; FIX3, W6, CNT / END, SEND, CEND;
                    // ZERO, ZPOS stay (written in this clock, pc + 1)
                    if (ub[UB_TO_STG] || (op_diff && front_done)) est <= E_STG;
                    else if (ub[UB_TO_PASS] || (op_ref && ref_ok) || (op_om && !mrun)) est <= E_PASS;
                    else if (ub[UB_TO_IDLE]) est <= E_IDLE;
                end
                E_STG: est <= E_LD;
                E_LD: est <= ub[UB_COPY] ? E_WR : E_PASS;
                E_PASS: begin
                    if (pass_end) begin
                        if (is_back) est <= E_OP;
                        else if (is_sat && ovf_now) est <= E_FIX;
                        else est <= E_WR;
                        if (is_fix3) omega <= om;           // complete since bit 31
                    end
                end
                E_FIX: if (fix_end) est <= E_WR;
                E_WR: est <= (is_fix3 && !task_pos) ? E_WR2 : E_OP;
                default: est <= E_OP;                       // E_WR2
            endcase
            // Program entry (pc_next jumps): after the step states, so that it wins over them.
            // go_stat / go_sw start from E_IDLE only; a control trigger may interrupt a sweep in
            // any clock, including its E_OP clocks, whose own next state once won here (a counter
            // op entered its pass with the first control instruction; the end marker dropped to
            // E_IDLE and the control period stalled into an overrun).
            if (go_ctl || go_stat || go_sw) est <= E_OP;

            // ---- multiplier: starts with the W5 pass (step mk = pass bit j) ----
            if (m_start)
                mrun <= 1'b1;
            else if (mrun && m_end)
                mrun <= 1'b0;
        end
    end

    // datapath registers
    always @(posedge clk) begin
        // X: shift / parallel load (the OR of the stages; X is 0 before a load)
        if (x_clr || rst)
            x <= {XW{1'b0}};
        else if (x_shift || x_load)
            x <= {x_shift & x_in, x[XW-1:IW+1], {IW{1'b0}}} | g_all;     // x[IW:1] is in g_lo
        // ALU carry: before the first ALU bit 1 (subtract), rnd (speed reference, OM: ka rounding
        // bit) or 1 + rnd (position reference: subtract and round)
        if (!in_pass || !p_al) begin
            if (op_ref) begin
                c0 <= task_pos ? ~ref_q : ref_q;       // the value of the clock j = ja - 1 stays
                c1 <= task_pos & ref_q;
            end else begin
                c0 <= op_sub;                          // (OM: the rounding bit enters u1)
                c1 <= 1'b0;
            end
        end else begin
            c0 <= maj ^ c1;
            c1 <= maj & c1;
        end
        if (in_pass && p_ca) a_h <= a_raw;                   // sign of a 32-bit A (bit 31)
        if (in_pass && p_cb) b_h <= b_raw;                   // sign of B (bit 17 or 31)
        // POS pass: dpos sign sd, spd = dpos << 16 overflows if dpos bits 31..15 are not all equal
        if (in_pass && is_pos) begin
            if (p_f1) begin                                   // bit 15
                sd <= r;
                spd_ovf <= 1'b0;
            end else if (p_f2 && r != sd) spd_ovf <= 1'b1;
            if (p_f3) sd <= r;                                // bit 31
        end
        // OM pass: omega overflows if result bits 39..31 are not all equal; om_sgn = bit 39
        if (in_pass && is_om) begin
            if (p_f1) begin                                   // bit 31
                om_ovf <= 1'b0;
                om_sgn <= r;
            end else if (p_f2 && r != om_sgn) om_ovf <= 1'b1;
            if (p_f3) om_sgn <= r;                            // bit 39
        end
        // position reference pass: rounding bit (bit 23), any result bit 24.. set (wrap detection)
        if (in_pass && is_ref && task_pos) begin
            if (p_f1) begin
                rnd <= a_raw;
                nz <= 1'b0;
            end else if (p_f2 && r) nz <= 1'b1;
        end
        // SW-bit saturation of the word in X: reference bit G at result bit SW-1, then compare
        if (!in_pass) begin
            w_trk <= 1'b0;
            w_ovf <= 1'b0;
        end else if (pw[PT_G]) begin
            w_trk <= 1'b1;
            w_r <= r;
        end else if (w_trk && r != w_r) begin
            w_ovf <= 1'b1;
        end
        if (pass_end) fix_sgn <= sgn_now;
        // rings (shift windows from the pass table)
        if (in_pass && p_r1 && is_pos) pp <= {a_bit, pp[PW-1:1]};
        else if (in_pass && p_r1 && is_ref) pp <= {pp[0], pp[PW-1:1]};
        if (in_pass && p_r3) dp <= {is_pos & r, dp[PW-1:1]};
        if (in_pass && p_r1 && is_diff && !diff_q) idp <= {a_bit, idp[IW-1:1]};
        if (in_pass && p_r1 && is_diff && diff_q) iqp <= {a_bit, iqp[IW-1:1]};
        if (in_pass && p_r1 && is_w6) omp <= {a_bit, omp[WW-1:1]};
        if (in_pass && p_r2) om <= {r, om[WW-1:1]};
        // load estimate: OM pass (40 bits): u1, t2 into ldt, spd into spp; LD pass: D += t2 >>> ls+1
        if (in_pass && is_om) begin
            ldd <= {ldd[0], ldd[39:1]};
            ldt <= {t2b, ldt[39:1]};
            u1d <= u1b;
            cu0 <= u1m ^ cu1;
            cu1 <= u1m & cu1;
            cs1 <= (u1d & ~a_bit) | (cs1 & (u1d ^ ~a_bit));
            cs2 <= (s1b & sppb) | (cs2 & (s1b ^ sppb));
            if (j < 6'd32) spp <= {a_bit, spp[WW-1:1]};
            if (j == 6'd31) sph <= spp[0];
        end else if (in_pass && is_ld) begin
            ldd <= {ldb, ldd[39:1]};
            ldt <= {ldt[39], ldt[39:1]};
            cl <= (ldd[0] & ltap) | (cl & (ldd[0] ^ ltap));
        end else begin
            u1d <= 1'b0;
            cu0 <= ~ka[0];
            cu1 <= ka[0];
            cs1 <= 1'b1;
            cs2 <= 1'b0;
            cl <= 1'b0;
        end
        // multiplier: s + 40 steps through ka, which keeps the last 41 product bits (mk, ms: not
        // reset by rst, m_start loads them before mrun rises)
        if (m_start) begin
            mk <= 7'd89;                                     // -39
            ms <= 19'sd0;
            ka <= 41'd0;
        end else if (mrun) begin
            mk <= mk + 7'd1;
            ms <= msum >>> 1;
            ka <= {msum[0], ka[40:1]};
        end else if (in_pass && is_om) begin
            ka <= {1'b0, ka[40:1]};
        end
        if (in_pass && is_diff && p_cb) msg <= x[0];        // i_q sign (bit 17 of the W5 pass)
        if (rst) begin
            ldd <= 40'd0;
            spp <= {WW{1'b0}};
            pp <= {PW{1'b0}};
            idp <= {IW{1'b0}};
            iqp <= {IW{1'b0}};
            omp <= {WW{1'b0}};
        end
    end

    // =================================== interfaces ===================================
    // MPC core input buffer (dx0, dx1 at y0 + 4, y1 + 4; the second FIX3 write: y2 = omega,
    // at omega - 1)
    assign core_in_wdata = x[SW-1:0];
    assign core_in_we    = (est == E_WR) || (est == E_WR2) || wr_zero || (in_pass && p_w0);
    assign core_in_addr  = {u_wa[5:3], u_wa[2] | (est == E_WR && is_diff), u_wa[1], u_wa[0] & (est != E_WR2)};
    // reference readout
    assign ref_age = uw[UW_AGE +: AW];
    assign ref_bit = j;
    // status words: REF (w_k window, reference pass m = 0), I_D / I_Q (DIFF passes, A = i_d /
    // i_q), SPEED (FIX3 pass, result), U_D / U_Q (status passes, A = u); sweep words (CNT
    // steps): the bits come from axis_status, st_d is not used
    assign st_sh   = in_pass && p_ss;
    assign st_d    = is_fix3 ? r : a_raw;
    assign st_wr   = pass_end && is_stw;
    assign st_addr = uw[UW_ST +: 6];
    assign st_bit  = j_nx[4:0];
    assign sw_go   = go_sw;
    assign sw_end  = (est == E_OP) && ub[UB_CEND];
    assign ctl_go  = go_ctl;

    // the op code stays in the microword (the test bench reads it), so do the source's upper bits;
    // the words' top bits are spare
    wire unused = &{1'b0, uw[UW_SRC-1:0], uw[UW_SRC+3:UW_SRC+1], uw[UW_AGE + 3],
                    ub[35:UB_LD+1], per_cnt};   // (age bit 3: N = 8 only)
endmodule
`default_nettype wire
