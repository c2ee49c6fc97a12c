// ctrl_seq: per-axis control sequencer (paper 000 Fig. 3, sec. V-A).
//
// Every PWM period, at the ADC trigger (period centre), it latches the
// electrical angle theta_trig and the encoder count, and when the ADC samples
// arrive it runs the modulation chain for the held u_dq:
//   theta_mod = theta_trig + (theta_trig - theta_trig_prev)   (one PWM period ahead:
//               the angle in the middle of the period the new duties are applied)
//   xform mod: inv_park(u, theta_mod) -> inv_clarke -> min_sub -> duty_scale(kdc) -> cmp, cmp_load
// In the last PWM period of each control period (pwm_per_control periods), before
// the modulation it runs the control law:
//   xform front: clarke(i_abc) -> park(theta_trig) -> i_d, i_q
//   omega = sat32((pos_trig - pos_prev) << 16) + rshift_round(kacc * i_q, kacc_shift)
//           (eq. 37 in counts per Ts, plus the (Ts/2) acceleration term); the count is
//           delayed by THETA_LAT so that it is the count theta_trig was computed from
//   core inputs (raw units), written one word per clock into the core's input buffer:
//   y = (i_d, i_q, omega | 0), omega, dx = x_k - x_{k-1}, u_prev, ebar_prev, and the
//   references w_k..w_{k+N} from ref_gen (Q.32) -> Q16.16 speed or, for the position
//   task, Q32.8 relative to the measured count (modulo 2^32, so the encoder wrap is
//   harmless; the core's own translation then subtracts 0); one shared subtract/round/
//   saturate formats the references one per clock
//   -> mpc_core start/done -> u, ebar (kept here as the loop state).
// With run = 0 the law is skipped and u = ebar = 0 (bridges, if enabled, see zero voltage).
//
// Ports: see below; formats are those of empc_formats.vh.  The bit-accurate model is
// gen/empc/rtlmodel/ctrl_seq.py.
// Latency: adc_trig -> cmp_load is reported on `latency` (clocks) every period; it must
// end before the next period boundary (PWM_HALF_PERIOD clocks after the trigger), else
// `overrun` pulses at the boundary and the previous compare values stay.
// Reset: state idle, u = ebar = 0, previous-sample registers 0, first-period flag set.
`default_nettype none
`include "empc_formats.vh"
module ctrl_seq #(
    parameter integer N = `EMPC_N,
    parameter integer CW = $clog2(`EMPC_PWM_HALF_PERIOD + 1),
    parameter integer THETA_LAT = 4     // pos_sense: clocks from a count to its angle
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
    input  wire signed [`EMPC_I_W-1:0]    id_ref,
    input  wire signed [`EMPC_I_W-1:0]    iq_ref,
    input  wire                           task_pos,        // active coefficient bank: position task
    // reference generator
    output reg                            ref_advance,
    input  wire [(N+1)*64-1:0]            ref_w,           // w_k .. w_{k+N}, Q.32
    // MPC core
    output reg                            core_start,
    output reg                            core_in_we,      // input buffer (map: EMPC_IN_* / mpc_core.py)
    output reg  [5:0]                     core_in_addr,
    output reg  signed [`EMPC_SIG_W-1:0]  core_in_wdata,
    input  wire                           core_done,
    input  wire [2*`EMPC_U_W-1:0]         core_u,
    input  wire [3*`EMPC_SIG_W-1:0]       core_ebar,
    // PWM
    output reg  [3*CW-1:0]                cmp,
    output reg                            cmp_load,
    // status
    output reg                            control_done,    // pulse: a control period completed
    output reg                            overrun,         // pulse: computation missed the boundary
    output reg                            front_sat,       // pulse: a front-end block saturated
    output reg  [15:0]                    latency,
    output reg  signed [`EMPC_I_W-1:0]    i_d,
    output reg  signed [`EMPC_I_W-1:0]    i_q,
    output reg  signed [`EMPC_W_W-1:0]    omega,
    output reg  signed [`EMPC_U_W-1:0]    u_d,
    output reg  signed [`EMPC_U_W-1:0]    u_q,
    output reg  [`EMPC_ANGLE_BITS-1:0]    theta_trig
);
    localparam integer SW = `EMPC_SIG_W;
    localparam integer UW = `EMPC_U_W;
    localparam integer IW = `EMPC_I_W;
    localparam integer WW = `EMPC_W_W;
    localparam integer AB = `EMPC_ANGLE_BITS;
    localparam integer PW = `EMPC_POS_W;
    localparam integer TH_SH = 32 - `EMPC_TH_FRAC;           // ref Q.32 -> position Q.8
    localparam integer W_SH = 32 - `EMPC_W_FRAC;             // ref Q.32 -> speed Q.16

    localparam [3:0] S_IDLE = 4'd0, S_ADC = 4'd1, S_FRONT = 4'd2, S_OMEGA = 4'd3, S_OMEGA2 = 4'd4,
                     S_WRITE = 4'd5, S_CORE = 4'd6, S_MOD = 4'd7, S_MOD_WAIT = 4'd8;
    reg [3:0] state;
    localparam [2:0] OMEGA_WAIT = 3'd4;  // i_q -> ka_b -> ka_p -> ka_t -> omega_r

    // ---------------- helpers ----------------
    function signed [SW-1:0] sat_sw;                 // saturate a 66-bit value to SIG_W
        input signed [65:0] v;
        begin
            if (v > $signed({{(67-SW){1'b0}}, {(SW-1){1'b1}}}))
                sat_sw = {1'b0, {(SW-1){1'b1}}};
            else if (v < $signed({{(66-SW){1'b1}}, 1'b1, {(SW-1){1'b0}}}))
                sat_sw = {1'b1, {(SW-1){1'b0}}};
            else
                sat_sw = v[SW-1:0];
        end
    endfunction

    function signed [65:0] rsr;                      // rshift_round of a signed 64-bit value
        input signed [63:0] v;
        input integer n;
        reg signed [65:0] t;
        begin
            t = {{2{v[63]}}, v} + (66'sd1 <<< (n - 1));
            rsr = t >>> n;
        end
    endfunction

    // ---------------- per-period bookkeeping ----------------
    reg  [7:0]  per_cnt;            // PWM periods since the last control period
    reg         is_control;
    reg         first;
    reg  [AB-1:0] theta_mod;
    reg  [PW-1:0] pos_trig, pos_prev;
    reg  signed [IW-1:0] id_prev, iq_prev;
    reg  signed [WW-1:0] omega_prev;
    reg  signed [UW-1:0] u_st0, u_st1;
    reg  [3*SW-1:0] ebar_st;
    reg  [15:0] lat_cnt;
    reg         busy_period;        // between the trigger and cmp_load


    // ---------------- transform chain: one microprogrammed MAC (xform) ----------------
    reg  xf_front, xf_mod;
    wire xf_busy, xf_done, xf_sat;
    wire signed [IW-1:0] xf_d, xf_q;
    wire [CW-1:0] cmp_a, cmp_b, cmp_c;
    xform u_xform (.clk(clk), .rst(rst), .start_front(xf_front), .start_mod(xf_mod),
                   .angle(xf_front ? theta_trig : theta_mod),
                   .i_a(cur0), .i_b(cur1), .i_c(cur2), .u_d(u_st0), .u_q(u_st1), .kdc(kdc),
                   .busy(xf_busy), .done(xf_done), .sat(xf_sat), .i_d(xf_d), .i_q(xf_q),
                   .cmp_a(cmp_a), .cmp_b(cmp_b), .cmp_c(cmp_c));

    // the count that belongs to `theta` (pos_sense needs THETA_LAT clocks from count to angle)
    reg [PW-1:0] pos_dl [0:THETA_LAT-1];
    integer di;
    always @(posedge clk) begin
        pos_dl[0] <= pos;
        for (di = 1; di < THETA_LAT; di = di + 1) pos_dl[di] <= pos_dl[di-1];
    end
    wire [PW-1:0] pos_theta = pos_dl[THETA_LAT-1];

    // eq. 37: counts per Ts in Q16.16, saturated to W_W
    wire signed [PW-1:0] dpos_c = pos_trig - pos_prev;
    wire signed [PW+`EMPC_W_FRAC:0] spd_full = {dpos_c[PW-1], dpos_c, {`EMPC_W_FRAC{1'b0}}};
    wire spd_ovf = (spd_full > $signed({{(PW+`EMPC_W_FRAC+1-WW+1){1'b0}}, {(WW-1){1'b1}}})) ||
                   (spd_full < $signed({{(PW+`EMPC_W_FRAC+1-WW){1'b1}}, 1'b1, {(WW-1){1'b0}}}));
    wire signed [WW-1:0] speed_q = (spd_full > $signed({{(PW+`EMPC_W_FRAC+1-WW+1){1'b0}}, {(WW-1){1'b1}}})) ?
                                   {1'b0, {(WW-1){1'b1}}} :
                                   (spd_full < $signed({{(PW+`EMPC_W_FRAC+1-WW){1'b1}}, 1'b1, {(WW-1){1'b0}}})) ?
                                   {1'b1, {(WW-1){1'b0}}} : spd_full[WW-1:0];

    // speed-estimate acceleration term: one registered 18x18 product (one DSP48A1), then
    // round/shift and the saturating sum each in their own register stage
    reg  signed [17:0] ka_a, ka_b;
    reg  signed [35:0] ka_p;
    reg  signed [36:0] ka_t;
    reg  signed [WW-1:0] omega_r;
    reg                  omega_ovf_r;
    wire signed [36:0] ka_round = {ka_p[35], ka_p} + ((kacc_shift == 5'd0) ? 37'sd0 : (37'sd1 <<< (kacc_shift - 5'd1)));
    wire signed [37:0] omega_sum = {{6{speed_q[WW-1]}}, speed_q} + {ka_t[36], ka_t};
    wire               omega_ovf = (omega_sum > $signed({7'd0, {(WW-1){1'b1}}})) ||
                                   (omega_sum < $signed({6'h3f, 1'b1, {(WW-1){1'b0}}}));
    always @(posedge clk) begin
        ka_a <= kacc;
        ka_b <= i_q;
        ka_p <= ka_a * ka_b;
        ka_t <= ka_round >>> kacc_shift;
        omega_r <= (omega_sum > $signed({7'd0, {(WW-1){1'b1}}})) ? {1'b0, {(WW-1){1'b1}}} :
                   (omega_sum < $signed({6'h3f, 1'b1, {(WW-1){1'b0}}})) ? {1'b1, {(WW-1){1'b0}}} :
                   omega_sum[WW-1:0];
        omega_ovf_r <= omega_ovf || spd_ovf;
    end

    // ---------------- core input formatting ----------------
    wire signed [PW-1:0] dpos = dpos_c;                        // modular difference: counts per Ts
    wire signed [IW:0]   did  = {i_d[IW-1], i_d} - {id_prev[IW-1], id_prev};
    wire signed [IW:0]   diq  = {i_q[IW-1], i_q} - {iq_prev[IW-1], iq_prev};
    wire signed [WW:0]   dom  = {omega[WW-1], omega} - {omega_prev[WW-1], omega_prev};
    // one core input word per clock: word index -> value (references through one
    // shared 64-bit subtract, registered, then round + saturate)
    localparam [5:0] IN_LAST_FIXED = 6'd13, IN_WREF = 6'd16;
    localparam [5:0] IN_END = IN_WREF + 6'd3 * N[5:0] + 6'd3;        // one past the last word
    reg  [5:0]  wr_idx;                 // word being prepared (stage 1)
    reg         wr_busy;
    reg  [5:0]  wr_m;                   // reference sample m of word wr_idx
    reg  [1:0]  wr_o;                   // output o of word wr_idx
    reg         s1_valid;
    reg  [5:0]  s1_addr;
    reg  signed [SW-1:0] s1_fixed;      // value of a non-reference word
    reg         s1_isref;
    reg  signed [63:0]   s1_ref;        // speed: ref; position: ref - count (mod 2^64)
    wire signed [63:0] ref_sel = ref_w[wr_m*64 +: 64];
    wire signed [SW-1:0] x_id = {{(SW-IW){i_d[IW-1]}}, i_d};
    wire signed [SW-1:0] x_iq = {{(SW-IW){i_q[IW-1]}}, i_q};
    wire signed [SW-1:0] x_om = {{(SW-WW){omega[WW-1]}}, omega};
    wire signed [SW-1:0] x_did = {{(SW-IW-1){did[IW]}}, did};
    wire signed [SW-1:0] x_diq = {{(SW-IW-1){diq[IW]}}, diq};
    wire signed [SW-1:0] x_dom = {{(SW-WW-1){dom[WW]}}, dom};
    wire signed [SW-1:0] x_u0 = {{(SW-UW){u_st0[UW-1]}}, u_st0};
    wire signed [SW-1:0] x_u1 = {{(SW-UW){u_st1[UW-1]}}, u_st1};
    wire signed [SW-1:0] x_idr = {{(SW-IW){id_ref[IW-1]}}, id_ref};
    wire signed [SW-1:0] x_iqr = {{(SW-IW){iq_ref[IW-1]}}, iq_ref};
    reg signed [SW-1:0] fixed_val;
    always @(*) begin
        case (wr_idx)
            6'd0: fixed_val = x_id;
            6'd1: fixed_val = x_iq;
            6'd2: fixed_val = task_pos ? {SW{1'b0}} : x_om;
            6'd3: fixed_val = x_om;
            6'd4: fixed_val = x_did;
            6'd5: fixed_val = x_diq;
            6'd6: fixed_val = x_dom;
            6'd7: fixed_val = {{(SW-PW-`EMPC_TH_FRAC){dpos[PW-1]}}, dpos, {`EMPC_TH_FRAC{1'b0}}};
            6'd9: fixed_val = x_u0;
            6'd10: fixed_val = x_u1;
            6'd11: fixed_val = ebar_st[0*SW +: SW];
            6'd12: fixed_val = ebar_st[1*SW +: SW];
            6'd13: fixed_val = ebar_st[2*SW +: SW];
            default: fixed_val = (wr_o == 2'd0) ? x_idr : x_iqr;   // 8 (dtau) reads 0 below
        endcase
    end

    // ---------------- sequencer ----------------
    reg [2:0] wait_cnt;
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
            state <= S_IDLE;
            per_cnt <= 8'd0;
            is_control <= 1'b0;
            first <= 1'b1;
            theta_trig <= {AB{1'b0}};
            theta_mod <= {AB{1'b0}};
            pos_trig <= {PW{1'b0}};
            pos_prev <= {PW{1'b0}};
            id_prev <= {IW{1'b0}};
            iq_prev <= {IW{1'b0}};
            omega_prev <= {WW{1'b0}};
            u_st0 <= {UW{1'b0}};
            u_st1 <= {UW{1'b0}};
            ebar_st <= {3*SW{1'b0}};
            lat_cnt <= 16'd0;
            latency <= 16'd0;
            busy_period <= 1'b0;
            wait_cnt <= 3'd0;
            cmp <= {3*CW{1'b0}};
            i_d <= {IW{1'b0}};
            i_q <= {IW{1'b0}};
            omega <= {WW{1'b0}};
            u_d <= {UW{1'b0}};
            u_q <= {UW{1'b0}};
            wr_idx <= 6'd0;
            wr_m <= 6'd0;
            wr_o <= 2'd0;
            wr_busy <= 1'b0;
            s1_valid <= 1'b0;
            s1_addr <= 6'd0;
            s1_isref <= 1'b0;
            s1_fixed <= {SW{1'b0}};
            s1_ref <= 64'sd0;
            core_in_we <= 1'b0;
            core_in_addr <= 6'd0;
            core_in_wdata <= {SW{1'b0}};
        end else begin
            if (busy_period)
                lat_cnt <= lat_cnt + 16'd1;
            if (period_start && busy_period && state != S_IDLE)
                overrun <= 1'b1;
            if (!run) begin
                u_st0 <= {UW{1'b0}};
                u_st1 <= {UW{1'b0}};
                ebar_st <= {3*SW{1'b0}};
            end
            // input-word pipeline: stage 1 registers the word, stage 2 rounds/saturates and writes
            s1_valid <= (state == S_WRITE) && wr_busy;
            s1_addr <= wr_idx;
            s1_isref <= (wr_idx >= IN_WREF) && (wr_o == 2'd2);
            s1_fixed <= (wr_idx == 6'd8) ? {SW{1'b0}} : fixed_val;
            s1_ref <= task_pos ? ref_sel - {pos_trig, 32'd0} : ref_sel;
            core_in_we <= s1_valid;
            core_in_addr <= s1_addr;
            core_in_wdata <= !s1_isref ? s1_fixed : task_pos ? sat_sw(rsr(s1_ref, TH_SH)) : sat_sw(rsr(s1_ref, W_SH));
            case (state)
                S_IDLE: if (adc_trig) begin
                    theta_trig <= theta;
                    theta_mod <= theta + (first ? {AB{1'b0}} : (theta - theta_trig));
                    first <= 1'b0;
                    pos_trig <= pos_theta;
                    busy_period <= 1'b1;
                    lat_cnt <= 16'd0;
                    if (per_cnt + 8'd1 >= pwm_per_control) begin
                        per_cnt <= 8'd0;
                        is_control <= 1'b1;
                        pos_sample <= 1'b1;
                        ref_advance <= 1'b1;
                    end else begin
                        per_cnt <= per_cnt + 8'd1;
                        is_control <= 1'b0;
                    end
                    state <= S_ADC;
                end
                S_ADC: if (adc_valid) begin        // xform samples the currents in this cycle
                    if (is_control) begin
                        xf_front <= 1'b1;
                        state <= S_FRONT;
                    end else
                        state <= S_MOD;
                end
                S_FRONT: if (xf_done) begin
                    if (xf_sat) front_sat <= 1'b1;
                    i_d <= xf_d;
                    i_q <= xf_q;
                    wait_cnt <= 3'd0;
                    state <= S_OMEGA;
                end
                S_OMEGA: begin                      // acceleration-term pipeline
                    wait_cnt <= wait_cnt + 3'd1;
                    if (wait_cnt == OMEGA_WAIT)
                        state <= S_OMEGA2;
                end
                S_OMEGA2: begin
                    omega <= omega_r;
                    if (omega_ovf_r) front_sat <= 1'b1;
                    if (run) begin
                        wr_idx <= 6'd0;
                        wr_m <= 6'd0;
                        wr_o <= 2'd0;
                        wr_busy <= 1'b1;
                        state <= S_WRITE;
                    end else begin
                        id_prev <= i_d;
                        iq_prev <= i_q;
                        omega_prev <= omega_r;
                        pos_prev <= pos_trig;
                        control_done <= 1'b1;
                        state <= S_MOD;
                    end
                end
                S_WRITE: begin                      // stage 1 issues words; stage 2 (above) writes them
                    if (wr_busy) begin
                        if (wr_idx == IN_LAST_FIXED) begin
                            wr_idx <= IN_WREF;
                        end else if (wr_idx >= IN_WREF) begin
                            if (wr_o == 2'd2) begin
                                wr_o <= 2'd0;
                                wr_m <= wr_m + 6'd1;
                            end else
                                wr_o <= wr_o + 2'd1;
                            wr_idx <= wr_idx + 6'd1;
                            if (wr_idx + 6'd1 == IN_END) wr_busy <= 1'b0;
                        end else
                            wr_idx <= wr_idx + 6'd1;
                    end else if (!s1_valid && !core_in_we) begin
                        id_prev <= i_d;
                        iq_prev <= i_q;
                        omega_prev <= omega;
                        pos_prev <= pos_trig;
                        core_start <= 1'b1;
                        state <= S_CORE;
                    end
                end
                S_CORE: if (core_done) begin
                    u_st0 <= core_u[0 +: UW];
                    u_st1 <= core_u[UW +: UW];
                    ebar_st <= core_ebar;
                    control_done <= 1'b1;
                    state <= S_MOD;
                end
                S_MOD: begin                        // xform samples u_st, theta_mod, kdc
                    xf_mod <= 1'b1;
                    u_d <= u_st0;
                    u_q <= u_st1;
                    state <= S_MOD_WAIT;
                end
                S_MOD_WAIT: if (xf_done) begin
                    if (xf_sat) front_sat <= 1'b1;
                    cmp <= {cmp_c, cmp_b, cmp_a};
                    cmp_load <= 1'b1;
                    latency <= lat_cnt + 16'd1;
                    busy_period <= 1'b0;
                    state <= S_IDLE;
                end
                default: state <= S_IDLE;
            endcase
        end
    end

    wire unused = &{1'b0, xf_busy};
endmodule
`default_nettype wire
