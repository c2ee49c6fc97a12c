// ctrl_seq: per-axis control sequencer (paper 000 Fig. 3, sec. V-A).
//
// Every PWM period, at the ADC trigger (period centre), it latches the
// electrical angle theta_trig and the encoder count, and when the ADC samples
// arrive it runs the modulation chain for the held u_dq:
//   theta_mod = theta_trig + (theta_trig - theta_trig_prev)   (one PWM period ahead:
//               the angle in the middle of the period the new duties are applied)
//   inv_park(u, theta_mod) -> inv_clarke -> min_sub -> duty_scale(kdc) -> cmp, cmp_load
// In the last PWM period of each control period (pwm_per_control periods), before
// the modulation it runs the control law:
//   clarke(i_abc) -> park(theta_trig) -> i_d, i_q
//   omega = sat32((pos_trig - pos_prev) << 16) + rshift_round(kacc * i_q, kacc_shift)
//           (eq. 37 in counts per Ts, plus the (Ts/2) acceleration term); the count is
//           delayed by THETA_LAT so that it is the count theta_trig was computed from
//   core inputs (raw units): y = (i_d, i_q, omega | 0), dx = x_k - x_{k-1},
//   references w_k..w_{k+N} from ref_gen (Q.32) -> Q16.16 speed or, for the position
//   task, Q32.8 relative to the measured count (modulo 2^32, so the encoder wrap is
//   harmless; the core's own translation then subtracts 0), u_prev, ebar_prev
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
    output reg  signed [`EMPC_OPW-1:0]    core_y0,
    output reg  signed [`EMPC_OPW-1:0]    core_y1,
    output reg  signed [`EMPC_SIG_W-1:0]  core_y2,
    output reg  signed [`EMPC_W_W-1:0]    core_omega,
    output reg  [5*`EMPC_SIG_W-1:0]       core_dx,
    output reg  [(N+1)*3*`EMPC_SIG_W-1:0] core_wref,
    output wire [2*`EMPC_U_W-1:0]         core_u_prev,
    output wire [3*`EMPC_SIG_W-1:0]       core_ebar_prev,
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
    localparam integer VW = `EMPC_V_W;
    localparam integer WW = `EMPC_W_W;
    localparam integer AB = `EMPC_ANGLE_BITS;
    localparam integer PW = `EMPC_POS_W;
    localparam integer TW = `EMPC_TRIG_W;
    localparam integer UV_SH = `EMPC_U_FRAC - `EMPC_V_FRAC;   // u (Q.8) -> transform voltage (Q.4)
    localparam integer TH_SH = 32 - `EMPC_TH_FRAC;           // ref Q.32 -> position Q.8
    localparam integer W_SH = 32 - `EMPC_W_FRAC;             // ref Q.32 -> speed Q.16

    localparam [3:0] S_IDLE = 4'd0, S_ADC = 4'd1, S_CLARKE = 4'd2, S_TRIG_P = 4'd3, S_PARK = 4'd4,
                     S_OMEGA = 4'd5, S_OMEGA2 = 4'd6, S_CORE = 4'd7, S_TRIG_M = 4'd8, S_IPARK = 4'd9,
                     S_ICLARKE = 4'd10, S_MINSUB = 4'd11, S_DUTY = 4'd12;
    reg [3:0] state;

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

    function signed [VW-1:0] u_to_v;                 // Q16.8 (24 b) -> Q14.4 (18 b), round + saturate
        input signed [UW-1:0] v;
        reg signed [UW:0] t;
        begin
            t = $signed({v[UW-1], v}) + $signed({{UW{1'b0}}, 1'b1} << (UV_SH - 1));
            t = t >>> UV_SH;                         // t is signed: arithmetic shift
            if (t > $signed({{(UW+2-VW){1'b0}}, {(VW-1){1'b1}}}))
                u_to_v = {1'b0, {(VW-1){1'b1}}};
            else if (t < $signed({{(UW+1-VW){1'b1}}, 1'b1, {(VW-1){1'b0}}}))
                u_to_v = {1'b1, {(VW-1){1'b0}}};
            else
                u_to_v = t[VW-1:0];
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
    reg  signed [12:0] ia, ib, ic;
    reg  [15:0] lat_cnt;
    reg         busy_period;        // between the trigger and cmp_load
    reg         theta_pending;      // sincos result for Park pending

    assign core_u_prev = {u_st1, u_st0};
    assign core_ebar_prev = ebar_st;

    // ---------------- transform blocks ----------------
    reg         sc_valid_in;
    reg  [AB-1:0] sc_angle;
    wire        sc_valid_out;
    wire signed [TW-1:0] sc_sin, sc_cos;
    sincos u_sincos (.clk(clk), .rst(rst), .in_valid(sc_valid_in), .angle(sc_angle),
                     .out_valid(sc_valid_out), .sin_out(sc_sin), .cos_out(sc_cos));
    reg signed [TW-1:0] sin_r, cos_r;

    reg  cl_start;
    wire cl_done, cl_busy, cl_sat;
    wire signed [IW-1:0] i_alpha, i_beta;
    clarke u_clarke (.clk(clk), .rst(rst), .start(cl_start), .i_a(ia), .i_b(ib), .i_c(ic),
                     .busy(cl_busy), .done(cl_done), .i_alpha(i_alpha), .i_beta(i_beta), .sat(cl_sat));

    reg  pk_start;
    wire pk_done, pk_busy, pk_sat;
    wire signed [IW-1:0] pk_d, pk_q;
    park u_park (.clk(clk), .rst(rst), .start(pk_start), .i_alpha(i_alpha), .i_beta(i_beta),
                 .sin_in(sin_r), .cos_in(cos_r), .busy(pk_busy), .done(pk_done), .i_d(pk_d), .i_q(pk_q),
                 .sat(pk_sat));

    reg  ip_start;
    wire ip_done, ip_busy, ip_sat;
    wire signed [VW-1:0] u_alpha, u_beta;
    wire signed [VW-1:0] uv_d = u_to_v(u_st0);
    wire signed [VW-1:0] uv_q = u_to_v(u_st1);
    inv_park u_inv_park (.clk(clk), .rst(rst), .start(ip_start), .u_d(uv_d), .u_q(uv_q),
                         .sin_in(sin_r), .cos_in(cos_r), .busy(ip_busy), .done(ip_done),
                         .u_alpha(u_alpha), .u_beta(u_beta), .sat(ip_sat));

    reg  ic_start;
    wire ic_done, ic_busy, ic_sat;
    wire signed [VW-1:0] u_a, u_b, u_c;
    inv_clarke u_inv_clarke (.clk(clk), .rst(rst), .start(ic_start), .u_alpha(u_alpha), .u_beta(u_beta),
                             .busy(ic_busy), .done(ic_done), .u_a(u_a), .u_b(u_b), .u_c(u_c), .sat(ic_sat));

    reg  ms_start;
    wire ms_done, ms_busy, ms_sat;
    wire signed [VW-1:0] w_a, w_b, w_c;
    min_sub u_min_sub (.clk(clk), .rst(rst), .start(ms_start), .u_a(u_a), .u_b(u_b), .u_c(u_c),
                       .busy(ms_busy), .done(ms_done), .w_a(w_a), .w_b(w_b), .w_c(w_c), .sat(ms_sat));

    reg  ds_start;
    wire ds_done, ds_busy, ds_sat;
    wire [CW-1:0] cmp_a, cmp_b, cmp_c;
    duty_scale u_duty (.clk(clk), .rst(rst), .start(ds_start), .v_a(w_a), .v_b(w_b), .v_c(w_c), .kdc(kdc),
                       .busy(ds_busy), .done(ds_done), .cmp_a(cmp_a), .cmp_b(cmp_b), .cmp_c(cmp_c), .sat(ds_sat));

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

    // speed-estimate acceleration term: one registered 18x18 product (one DSP48A1)
    reg  signed [17:0] ka_a, ka_b;
    reg  signed [35:0] ka_p;
    always @(posedge clk) begin
        ka_a <= kacc;
        ka_b <= pk_q;
        ka_p <= ka_a * ka_b;
    end
    wire signed [36:0] ka_round = {ka_p[35], ka_p} + ((kacc_shift == 5'd0) ? 37'sd0 : (37'sd1 <<< (kacc_shift - 5'd1)));
    wire signed [36:0] ka_term = ka_round >>> kacc_shift;
    wire signed [37:0] omega_sum = {{6{speed_q[WW-1]}}, speed_q} + {ka_term[36], ka_term};
    wire               omega_ovf = (omega_sum > $signed({7'd0, {(WW-1){1'b1}}})) ||
                                   (omega_sum < $signed({6'h3f, 1'b1, {(WW-1){1'b0}}}));
    wire signed [WW-1:0] omega_sat = (omega_sum > $signed({7'd0, {(WW-1){1'b1}}})) ? {1'b0, {(WW-1){1'b1}}} :
                                     (omega_sum < $signed({6'h3f, 1'b1, {(WW-1){1'b0}}})) ? {1'b1, {(WW-1){1'b0}}} :
                                     omega_sum[WW-1:0];

    // ---------------- core input formatting ----------------
    wire signed [PW-1:0] dpos = dpos_c;                        // modular difference: counts per Ts
    wire signed [IW:0]   did  = {i_d[IW-1], i_d} - {id_prev[IW-1], id_prev};
    wire signed [IW:0]   diq  = {i_q[IW-1], i_q} - {iq_prev[IW-1], iq_prev};
    wire signed [WW:0]   dom  = {omega_sat[WW-1], omega_sat} - {omega_prev[WW-1], omega_prev};
    wire [5*SW-1:0] dx_next = {{SW{1'b0}},
                               {{(SW-PW-`EMPC_TH_FRAC){dpos[PW-1]}}, dpos, {`EMPC_TH_FRAC{1'b0}}},
                               {{(SW-WW-1){dom[WW]}}, dom},
                               {{(SW-IW-1){diq[IW]}}, diq},
                               {{(SW-IW-1){did[IW]}}, did}};
    wire [(N+1)*3*SW-1:0] wref_next;
    genvar g;
    generate
        for (g = 0; g <= N; g = g + 1) begin : g_ref
            wire signed [63:0] wv = ref_w[g*64 +: 64];
            wire signed [63:0] rel = wv - {pos_trig, 32'd0};        // modulo 2^64: wrap-safe
            assign wref_next[(3*g+0)*SW +: SW] = {{(SW-IW){id_ref[IW-1]}}, id_ref};
            assign wref_next[(3*g+1)*SW +: SW] = {{(SW-IW){iq_ref[IW-1]}}, iq_ref};
            assign wref_next[(3*g+2)*SW +: SW] = task_pos ? sat_sw(rsr(rel, TH_SH)) : sat_sw(rsr(wv, W_SH));
        end
    endgenerate

    // ---------------- sequencer ----------------
    reg [2:0] wait_cnt;
    always @(posedge clk) begin
        // default single-cycle pulses
        sc_valid_in <= 1'b0;
        cl_start <= 1'b0;
        pk_start <= 1'b0;
        ip_start <= 1'b0;
        ic_start <= 1'b0;
        ms_start <= 1'b0;
        ds_start <= 1'b0;
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
            ia <= 13'sd0;
            ib <= 13'sd0;
            ic <= 13'sd0;
            sc_angle <= {AB{1'b0}};
            sin_r <= {TW{1'b0}};
            cos_r <= {{(TW-AB-1){1'b0}}, 1'b1, {AB{1'b0}}};
            lat_cnt <= 16'd0;
            latency <= 16'd0;
            busy_period <= 1'b0;
            theta_pending <= 1'b0;
            wait_cnt <= 3'd0;
            cmp <= {3*CW{1'b0}};
            i_d <= {IW{1'b0}};
            i_q <= {IW{1'b0}};
            omega <= {WW{1'b0}};
            u_d <= {UW{1'b0}};
            u_q <= {UW{1'b0}};
            core_y0 <= {`EMPC_OPW{1'b0}};
            core_y1 <= {`EMPC_OPW{1'b0}};
            core_y2 <= {SW{1'b0}};
            core_omega <= {WW{1'b0}};
            core_dx <= {5*SW{1'b0}};
            core_wref <= {(N+1)*3*SW{1'b0}};
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
                        sc_angle <= theta;          // Park angle: at the sample
                        sc_valid_in <= 1'b1;
                        theta_pending <= 1'b1;
                    end else begin
                        per_cnt <= per_cnt + 8'd1;
                        is_control <= 1'b0;
                    end
                    state <= S_ADC;
                end
                S_ADC: begin
                    if (sc_valid_out && theta_pending) begin
                        sin_r <= sc_sin;
                        cos_r <= sc_cos;
                        theta_pending <= 1'b0;
                    end
                    if (adc_valid) begin
                        ia <= cur0;
                        ib <= cur1;
                        ic <= cur2;
                        if (is_control) begin
                            cl_start <= 1'b1;
                            state <= S_CLARKE;
                        end else
                            state <= S_TRIG_M;
                    end
                end
                S_CLARKE: begin
                    if (sc_valid_out && theta_pending) begin
                        sin_r <= sc_sin;
                        cos_r <= sc_cos;
                        theta_pending <= 1'b0;
                    end
                    if (cl_done) begin
                        if (cl_sat) front_sat <= 1'b1;
                        state <= S_TRIG_P;
                    end
                end
                S_TRIG_P: begin
                    if (sc_valid_out && theta_pending) begin
                        sin_r <= sc_sin;
                        cos_r <= sc_cos;
                        theta_pending <= 1'b0;
                    end
                    if (!theta_pending) begin
                        pk_start <= 1'b1;
                        state <= S_PARK;
                    end
                end
                S_PARK: if (pk_done) begin
                    if (pk_sat) front_sat <= 1'b1;
                    i_d <= pk_d;
                    i_q <= pk_q;
                    wait_cnt <= 3'd0;
                    state <= S_OMEGA;
                end
                S_OMEGA: begin                      // ka_a/ka_b, then the product register
                    wait_cnt <= wait_cnt + 3'd1;
                    if (wait_cnt == 3'd2)
                        state <= S_OMEGA2;
                end
                S_OMEGA2: begin
                    omega <= omega_sat;
                    if (omega_ovf || spd_ovf) front_sat <= 1'b1;
                    core_y0 <= i_d;
                    core_y1 <= i_q;
                    core_y2 <= task_pos ? {SW{1'b0}} : {{(SW-WW){omega_sat[WW-1]}}, omega_sat};
                    core_omega <= omega_sat;
                    core_dx <= dx_next;
                    core_wref <= wref_next;
                    id_prev <= i_d;
                    iq_prev <= i_q;
                    omega_prev <= omega_sat;
                    pos_prev <= pos_trig;
                    if (run) begin
                        core_start <= 1'b1;
                        state <= S_CORE;
                    end else begin
                        control_done <= 1'b1;
                        state <= S_TRIG_M;
                    end
                end
                S_CORE: if (core_done) begin
                    u_st0 <= core_u[0 +: UW];
                    u_st1 <= core_u[UW +: UW];
                    ebar_st <= core_ebar;
                    control_done <= 1'b1;
                    state <= S_TRIG_M;
                end
                S_TRIG_M: begin                     // sincos of the modulation angle
                    sc_angle <= theta_mod;
                    sc_valid_in <= 1'b1;
                    theta_pending <= 1'b1;
                    state <= S_IPARK;
                end
                S_IPARK: begin
                    if (sc_valid_out && theta_pending) begin
                        sin_r <= sc_sin;
                        cos_r <= sc_cos;
                        theta_pending <= 1'b0;
                        ip_start <= 1'b1;
                        u_d <= u_st0;
                        u_q <= u_st1;
                    end
                    if (ip_done) begin
                        if (ip_sat) front_sat <= 1'b1;
                        ic_start <= 1'b1;
                        state <= S_ICLARKE;
                    end
                end
                S_ICLARKE: if (ic_done) begin
                    if (ic_sat) front_sat <= 1'b1;
                    ms_start <= 1'b1;
                    state <= S_MINSUB;
                end
                S_MINSUB: if (ms_done) begin
                    if (ms_sat) front_sat <= 1'b1;
                    ds_start <= 1'b1;
                    state <= S_DUTY;
                end
                S_DUTY: if (ds_done) begin
                    if (ds_sat) front_sat <= 1'b1;
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

    wire unused = &{1'b0, cl_busy, pk_busy, ip_busy, ic_busy, ms_busy, ds_busy, u_d[0]};
endmodule
`default_nettype wire
