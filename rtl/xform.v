// xform: the whole transform chain (sin/cos, Clarke, Park, inverse Park, inverse Clarke,
// min-subtraction, DC-link scaling) on ONE multiply-accumulate unit (one DSP48A1), run by a
// microprogram.  Replaces sincos, clarke, park, inv_park, inv_clarke, min_sub, duty_scale.
//
//   front (start_front): (i_a, i_b, i_c, angle)  -> i_d, i_q              (paper 000 eqs. 32, 33)
//   mod   (start_mod):   (u_d, u_q, angle, kdc)  -> cmp_a, cmp_b, cmp_c    (u (Q.8) -> Q.4 as in
//                        ctrl_seq, eqs. 34-36, DC link)
//   Bit-exact to the step models of gen/empc/rtlmodel/xform_steps/ composed (xform.py front(), modulate());
//   the microprogram, its static schedule and its arithmetic are in xform.py (PROGRAM).
//
// Datapath, one microword (18 bit) per clock from the block RAM's second port:
//   stage 0  microword -> operand fetch into registers that are cleared unless selected:
//            RF_A (block RAM, results), RF_B (block RAM: sin, cos, -sin and constants), sine
//            nodes (block RAM port A), the sampled inputs, +-f (interpolation), kdc parts
//   stage 1  A = OR of the A-side registers, B = D + B0 (DSP pre-adder; one of them is 0)
//   stage 2  product register
//   stage 3  accumulator (48 bit in the DSP, 38 used): acc = (load ? C : acc) + product
//   stage 4  write-back: y = sat18(acc >>> 16), compare values min(acc >>> 16, HP), into
//            RF_A / RF_B / the minimum-select flags / the outputs (strobes from a destination
//            table in block RAM read at stage 3)
//   A1REG, B1REG, pre-adder, MREG, post-adder with the C/P select and PREG are one DSP48A1.
//   A row marked `wait` issues only when no pass is in flight (no result pending).
//
// Ports:
//   start_front      1-cycle request: i_a, i_b, i_c, angle sampled; ignored while busy
//   start_mod        1-cycle request: u_d, u_q, angle, kdc sampled; ignored while busy or
//                    together with start_front (front has priority)
//   angle            electrical angle, unsigned ANGLE_BITS (2^16 = 2 pi)
//   i_a, i_b, i_c    signed IN_W-bit phase currents (ADC LSB, adc_spi)
//   u_d, u_q         signed U_W (24) bit, Q.8 PWM ticks at the nominal DC link (the MPC's u);
//                    converted to Q.4 (round half up, saturate to V_W, no sat flag) first
//   kdc              unsigned KDC_W (18) bit Udc_nom / Udc, 1.0 = 2^16
//   busy             high from the cycle after an accepted start up to the cycle before done
//                    (a start in the done cycle is accepted)
//   done             1-cycle pulse: the outputs of the operation are updated in this cycle
//   sat              1-cycle pulse with done if a step saturated (front: clarke, park;
//                    mod: inv_park, inv_clarke, min_sub, duty_scale clamp)
//   i_d, i_q         signed I_W (18) bit, Q.4 ADC LSB; updated only by the done of a front op
//   cmp_a..c         unsigned CW-bit compare values 0..PWM_HALF_PERIOD; only by a mod done
//   mul_b, prod      the DSP's idle time after a front lent to the sequencer (its kacc * i_q):
//                    mul_b (signed 18 bit) is sampled in the clock before a front's done; prod
//                    = mul_b * i_q (signed 36 bit, exact: the accumulator) from the third clock
//                    after done, held until the first row of the next operation reaches the
//                    accumulator (the fourth clock after its start at the earliest)
// Parameters: IN_W (13, at most 14), PWM_HALF_PERIOD, CW (as pwm_center).
// Latency (start cycle -> done cycle): front 23, mod 84 cycles (xform.latency(), tested).
// Resources: 1 DSP48A1 (shared with the sequencer's kacc * i_q: mul_b, prod), 1 RAMB16 (sine nodes + microprogram), 3 RAMB8 (RF_A, RF_B, destination
//   table).
// Reset: control, pipeline and output registers clear (outputs 0, not busy; an operation in
//   flight is dropped).  The register files are not reset: every entry an operation reads is
//   written by that operation first, or is a constant (RF_B initial contents).  Neither are the
//   operand registers: a row's operands count only if it was issued (v1 is reset).
`default_nettype none
`include "empc_formats.vh"
module xform #(
    parameter integer IN_W            = `EMPC_ADC_BITS + 1,
    parameter integer PWM_HALF_PERIOD = `EMPC_PWM_HALF_PERIOD,
    parameter integer CW              = $clog2(PWM_HALF_PERIOD + 1)
) (
    input  wire                          clk,
    input  wire                          rst,
    input  wire                          start_front,
    input  wire                          start_mod,
    input  wire [`EMPC_ANGLE_BITS-1:0]   angle,
    input  wire signed [IN_W-1:0]        i_a,
    input  wire signed [IN_W-1:0]        i_b,
    input  wire signed [IN_W-1:0]        i_c,
    input  wire signed [`EMPC_U_W-1:0]   u_d,
    input  wire signed [`EMPC_U_W-1:0]   u_q,
    input  wire [`EMPC_KDC_W-1:0]        kdc,
    input  wire signed [`EMPC_OPW-1:0]   mul_b,
    output reg                           busy,
    output reg                           done,
    output reg                           sat,
    output reg  signed [`EMPC_I_W-1:0]   i_d,
    output reg  signed [`EMPC_I_W-1:0]   i_q,
    output reg  [CW-1:0]                 cmp_a,
    output reg  [CW-1:0]                 cmp_b,
    output reg  [CW-1:0]                 cmp_c,
    output wire signed [2*`EMPC_OPW-1:0] prod
);
    localparam integer W    = `EMPC_OPW;            // 18: every word (I_W = V_W = TRIG_W = KDC_W)
    localparam integer SH   = `EMPC_TRIG_FRAC;      // 16: output window acc >>> 16
    localparam integer PW   = 2 * W;                // 36: product
    localparam integer AW   = PW + 2;               // 38: accumulator bits used (|acc| < 2^37)
    localparam integer UW   = `EMPC_U_W;            // 24: u_d, u_q
    localparam integer ULB  = UW - W;               // 6: u = 64 uh + ul
    localparam integer AB   = `EMPC_ANGLE_BITS;     // 16
    localparam integer QB   = AB - 2;               // 14 bits inside a quadrant
    localparam integer FB   = 5;                    // interpolation bits (512 intervals per quadrant)
    localparam integer KLB  = `EMPC_KDC_FRAC + `EMPC_V_FRAC - SH;   // 4: kdc = 16 kh + kl
    localparam integer RAW  = 10;                   // block RAM address: 1024 x 18
    localparam [31:0]  HP32 = PWM_HALF_PERIOD;
    localparam [W-1:0] HPW  = HP32[W-1:0];

    // microword codes, entry points, RF_B constants (generated from xform.py)
`include "xform_ucode.vh"

    generate if (IN_W > 14 || W != 18 || `EMPC_I_W != W || `EMPC_V_W != W || `EMPC_TRIG_W != W ||
                 `EMPC_KDC_W != W || KLB != 4 || AB != 16 || ULB != 6 ||
                 `EMPC_U_FRAC - `EMPC_V_FRAC != 4) begin : g_bad_params
        xform_unsupported_parameters u_error ();   // no such module: elaboration stops here
    end endgenerate

    // ---------------- sampled inputs ----------------
    wire acc_front = start_front && !busy;
    wire acc_mod   = start_mod && !start_front && !busy;
    reg  [AB-1:0]          r_ang;
    reg  signed [IN_W-1:0] r_ia, r_ib, r_ic;
    reg  signed [UW-1:0]   r_ud, r_uq;
    reg  [W-1:0]           r_kdc;
    always @(posedge clk) begin
        if (rst) begin
            r_ang <= {AB{1'b0}};
            r_ia <= {IN_W{1'b0}}; r_ib <= {IN_W{1'b0}}; r_ic <= {IN_W{1'b0}};
            r_ud <= {UW{1'b0}}; r_uq <= {UW{1'b0}}; r_kdc <= {W{1'b0}};
        end else begin
            if (acc_front || acc_mod) r_ang <= angle;
            if (acc_front) begin
                r_ia <= i_a; r_ib <= i_b; r_ic <= i_c;
            end
            if (acc_mod) begin
                r_ud <= u_d; r_uq <= u_q; r_kdc <= kdc;
            end
        end
    end

    // ---------------- block RAM: sine nodes (port A) and microprogram (port B) ----------------
    reg [W-1:0] rom [0:(1 << RAW) - 1];
    integer k;
    initial begin
        for (k = 0; k < (1 << RAW); k = k + 1) rom[k] = {W{1'b0}};
`include "xform_rom.vh"
    end

    // ---------------- stage 0: microword, issue ----------------
    reg  [PCW-1:0] pc;                             // row in uc
    reg            run;
    reg  [W-1:0]   uc;                             // microword of row pc (block RAM port B)
    wire [4:0]     u_a    = uc[4:0];
    wire [4:0]     u_b    = uc[9:5];
    wire [1:0]     u_csel = uc[11:10];
    wire           u_wait = uc[12];
    wire [4:0]     u_dst  = uc[17:13];

    // pipeline control: valid, accumulator load, trig sign, destination
    reg        v1, v2, v3;
    reg        h1, h2, h3, h4;                  // valid and with a write-back (dst != D_NONE)
    reg [1:0]  c1, c2;
    reg        n1, n2;
    reg [4:0]  d1, d2, d3;
    wire       pend  = h1 || h2 || h3 || h4;
    wire       issue = run && !(u_wait && pend);
    wire       fin;                                                    // final write-back
    wire [PCW-1:0] pc_next = acc_front ? PC_FRONT : acc_mod ? PC_MOD : pc + {{(PCW-1){1'b0}}, issue};

    always @(posedge clk) begin
        if (rst) begin
            pc <= {PCW{1'b0}}; run <= 1'b0; busy <= 1'b0; uc <= {W{1'b0}};
        end else begin
            pc <= pc_next;
            uc <= rom[UC_BASE | {{(RAW-PCW){1'b0}}, pc_next}];
            if (fin) busy <= 1'b0;
            if (acc_front || acc_mod) begin
                run  <= 1'b1;
                busy <= 1'b1;
            end else if (issue && (u_dst == D_IQ || u_dst == D_CMPC)) begin
                run <= 1'b0;                                           // last row issued
            end
        end
    end

    // sine rows (a = 16..21): kind S / C / MS in u_a[2:1], node T[k] (u_a[0] = 0) or T[k+1].
    // sin(a) = sin_q(a), cos(a) = sin_q(a + 2^14), -sin(a) = sin_q(a + 2^15); odd quadrants use
    // k = ~r[13:5] and f = ~r[4:0] + 1 (1..32), so no subtractor is needed (xform_steps/sincos.py).
    //   value = (T[k] (s (32 - f)) + T[k+1] (s f)) 2^11 + C,  s = -1 in the negative half
    wire           is_rom = (u_a[4:3] == 2'b10);
    wire           t_cos  = (u_a[2:1] == 2'b01);
    wire           t_ms   = (u_a[2:1] == 2'b10);
    wire           second = u_a[0];
    wire           odd    = r_ang[QB] ^ t_cos;
    wire           neg    = r_ang[AB-1] ^ (t_cos & r_ang[QB]) ^ t_ms;
    wire [QB-FB-1:0] kk   = r_ang[QB-1:FB] ^ {(QB-FB){odd}};               // node index k
    wire [RAW-1:0] rom_addr = {1'b0, kk} + {{(RAW-1){1'b0}}, second};         // k or k + 1
    // +-(32 - f) for T[k], +-f for T[k+1]: with x = r[4:0] and g = odd ^ second the magnitude
    // is g ? 32 - x : x, i.e. fs = c0 + (x ^ -h) + h with h = g ^ neg, c0 = g ? (neg ? -32 : 32) : 0
    wire           g      = r_ang[QB] ^ t_cos ^ ~second;    // odd ^ ~second: T[k] row uses 32 - f
    wire           h      = g ^ neg;
    wire [FB+1:0]  fs     = {g & neg, g, {FB{1'b0}}} + ({2'b00, r_ang[FB-1:0]} ^ {(FB+2){h}})
                          + {{(FB+1){1'b0}}, h};

    // ---------------- stage 0 -> 1: operand registers ----------------
    // Each is cleared (synchronous reset: no LUT) unless it is this row's source, so the
    // A operand is the OR of the A-side registers and the B operand the sum D + B0.
    // register files in block RAM (write port: write-back; read port: the registered operand
    // fetch with its clear as the output reset), not LUT-RAM (24 LUTs).  No read ever meets a
    // write of the same entry (xform.schedule()), so the ports' collision mode does not matter.
    (* ram_style = "block" *) reg [W-1:0] rf_a [0:15];
    (* ram_style = "block" *) reg [W-1:0] rf_b [0:15];
    initial begin
        for (k = 0; k < 16; k = k + 1) rf_b[k] = RFB_INIT[k*W +: W];
    end
    reg  [3:0]         sel_m1, sel_m;                                  // RF_A address of the minimum
    wire [3:0]         ra = (u_a == A_M1) ? sel_m1 : (u_a == A_M) ? sel_m : u_a[3:0];
    reg  [W-1:0]       rfa_q, rfb_q;
    reg  [W-2:0]       rom_q;                                          // sine node, <= 2^16
    reg  [IN_W-1:0]    xa_q, xb_q, xc_q;                               // i_a, i_b, i_c
    reg  [W-1:0]       xdh_q, xqh_q;                                   // u_d, u_q >> 6
    reg  [ULB-1:0]     xdl_q, xql_q;                                   // u_d, u_q & 63
    reg  [FB+1:0]      f_q;                                            // +-f or +-(32 - f)
    reg  [SH-1:0]      k_q;                                            // kdc >> 4 or (kdc & 15) << 12
    reg  [W-1:0]       xm_q, km_q;                                     // mul_b * i_q: i_q, mul_b
    reg                mp1, mp2, mp3;                                  // that product in stage 1, 2, 3
    wire               mo;                                             // front's final write-back
    wire [W-1:0]       y;                                              // stage 4 result
    wire [W-KLB-1:0]   kh = r_kdc[W-1:KLB];
    wire [KLB-1:0]     kl = r_kdc[KLB-1:0];
    // (no rst: a row's operands are used only if it was issued, and v1 is reset)
    always @(posedge clk) begin
        // mo: the clock after the front's last row, no row issues; the row then in uc (not
        // issued) must not load its operands, the multiplier takes i_q (y) and mul_b
        rfa_q <= (u_a[4] || mo)      ? {W{1'b0}}    : rf_a[ra];
        rom_q <= (!is_rom || mo)     ? {(W-1){1'b0}} : rom[rom_addr][W-2:0];
        xa_q  <= (u_a != A_IA16 || mo) ? {IN_W{1'b0}} : r_ia;
        xb_q  <= (u_a != A_IB4 || mo)  ? {IN_W{1'b0}} : r_ib;
        xc_q  <= (u_a != A_IC4 || mo)  ? {IN_W{1'b0}} : r_ic;
        xdh_q <= (u_a != A_UHD || mo)  ? {W{1'b0}}    : r_ud[UW-1:ULB];
        xqh_q <= (u_a != A_UHQ || mo)  ? {W{1'b0}}    : r_uq[UW-1:ULB];
        xdl_q <= (u_a != A_ULD || mo)  ? {ULB{1'b0}}  : r_ud[ULB-1:0];
        xql_q <= (u_a != A_ULQ || mo)  ? {ULB{1'b0}}  : r_uq[ULB-1:0];
        rfb_q <= (u_b[4] || mo)      ? {W{1'b0}}    : rf_b[u_b[3:0]];
        f_q   <= (u_b != B_F || mo)  ? {(FB+2){1'b0}} : fs;
        k_q   <= (u_b == B_F || !u_b[4] || mo) ? {SH{1'b0}} :
                 (u_b == B_KH) ? {{(SH-W+KLB){1'b0}}, kh} : {kl, {(SH-KLB){1'b0}}};
        xm_q  <= mo ? y : {W{1'b0}};
        km_q  <= mo ? mul_b : {W{1'b0}};
    end
    always @(posedge clk) begin
        if (rst) begin
            v1 <= 1'b0; h1 <= 1'b0; c1 <= C_ACC; n1 <= 1'b0; d1 <= D_NONE;
        end else begin
            v1 <= issue; h1 <= issue && (u_dst != D_NONE); c1 <= u_csel; n1 <= neg; d1 <= u_dst;
        end
    end

    // ---------------- stage 1: operands ----------------
    wire signed [W-1:0] a_in = rfa_q | {1'b0, rom_q} | xdh_q | xqh_q
                             | {{(W-ULB){1'b0}}, xdl_q | xql_q}
                             | {{(W-IN_W-4){xa_q[IN_W-1]}}, xa_q, 4'b0000}       // 16 i_a
                             | {{(W-IN_W-2){xb_q[IN_W-1]}}, xb_q, 2'b00}         //  4 i_b
                             | {{(W-IN_W-2){xc_q[IN_W-1]}}, xc_q, 2'b00}         //  4 i_c
                             | xm_q;                                             // i_q (prod)
    wire signed [W-1:0] d_in = {f_q, {(W-FB-2){1'b0}}} | {{(W-SH){1'b0}}, k_q}   // +-f << 11 | kdc part
                             | km_q;                                             // mul_b (prod)
    wire signed [W-1:0] b_in = rfb_q;

    // ---------------- stages 1-3: one DSP48A1 ----------------
    reg  signed [W-1:0]  a_r, b_r;
    reg  signed [PW-1:0] prod_r;
    reg  signed [AW-1:0] p_r;
    // C: 0, 2^15 (round half up), 2^15 - 2^11 (negative sine, see xform.py)
    // (load, bit 15, bits 14..11 of C) for the stage-3 row: the table's second half, read with
    // (c2, n2) on its second port (the register is stage 3; only used while v3 is set)
    reg  [2:0]           cq;
    wire                 c_load = cq[2];
    wire signed [AW-1:0] c_val = {{(AW-SH){1'b0}}, cq[1], {4{cq[0]}}, {(SH-5){1'b0}}};
    always @(posedge clk) begin
        if (rst) begin
            a_r <= {W{1'b0}}; b_r <= {W{1'b0}}; prod_r <= {PW{1'b0}}; p_r <= {AW{1'b0}};
        end else begin
            a_r    <= a_in;                                            // A1REG
            b_r    <= d_in + b_in;                                     // pre-adder, B1REG
            prod_r <= a_r * b_r;                                       // MREG
            // post-adder, PREG (mp3: P = the product, held as prod until the next row's stage 3)
            if (v3 || mp3) p_r <= ((c_load || mp3) ? (mp3 ? {AW{1'b0}} : c_val) : p_r)
                                  + {{(AW-PW){prod_r[PW-1]}}, prod_r};
        end
    end
    always @(posedge clk) begin
        if (rst) begin
            mp1 <= 1'b0; mp2 <= 1'b0; mp3 <= 1'b0;
            v2 <= 1'b0; v3 <= 1'b0; h2 <= 1'b0; h3 <= 1'b0; h4 <= 1'b0; c2 <= C_ACC; n2 <= 1'b0;
            d2 <= D_NONE; d3 <= D_NONE;
        end else begin
            mp1 <= mo; mp2 <= mp1; mp3 <= mp2;
            v2 <= v1; v3 <= v2; h2 <= h1; h3 <= h2; h4 <= h3;
            c2 <= c1; n2 <= n1;
            d2 <= d1; d3 <= d2;
        end
    end

    // ---------------- stage 4: destination decode ----------------
    // A 32-entry table (block RAM) read with d3: its output register is the stage-4 decode of
    // the destination, reset unless the row has a write-back (h3), so that every strobe below is
    // one table bit, without decode logic.  Bits DQ_*; the RF_A / RF_B address is d[3:0].
    localparam integer DQ_AD = 0, DQ_WA = 4, DQ_WB = 5, DQ_F1 = 6, DQ_F2 = 7, DQ_ID = 8, DQ_IQ = 9,
                       DQ_CA = 10, DQ_CB = 11, DQ_CC = 12, DQ_CMP = 13, DQ_FIN = 14, DQ_SACC = 15;
    function [W-1:0] dclass;
        input [4:0] d;
        begin
            dclass = {W{1'b0}};
            dclass[DQ_AD +: 4] = d[3:0];
            dclass[DQ_WA] = !d[4];                                                 // RF_A
            dclass[DQ_WB] = (d[4:2] == 3'b100) && (d[1:0] != 2'b00);               // RF_B: S, C, MS
            dclass[DQ_F1] = (d == D_FLAG1);
            dclass[DQ_F2] = (d == D_FLAG2);
            dclass[DQ_ID] = (d == D_ID);
            dclass[DQ_IQ] = (d == D_IQ);
            dclass[DQ_CA] = (d == D_CMPA);
            dclass[DQ_CB] = (d == D_CMPB);
            dclass[DQ_CC] = (d == D_CMPC);
            dclass[DQ_CMP] = (d == D_CMPA) || (d == D_CMPB) || (d == D_CMPC);
            dclass[DQ_FIN] = (d == D_IQ) || (d == D_CMPC);
            // counts for sat: not a flag, not u_to_v (UDV, UQV)
            dclass[DQ_SACC] = (d != D_FLAG1) && (d != D_FLAG2) && (d[4:1] != D_UDV[4:1]);
        end
    endfunction
    // C select: load (c != C_ACC), C bit 15 (round half up: RND, or TRIG positive), C bits
    // 14..11 (TRIG negative: 2^15 - 2^11)
    function [W-1:0] cclass;
        input [1:0] c;
        input       n;
        cclass = {{(W-3){1'b0}}, c != C_ACC, (c == C_RND) || (c == C_TRIG && !n), c == C_TRIG && n};
    endfunction
    (* rom_style = "block" *) reg [W-1:0] dtab [0:63];     // 0..31 destinations, 32..39 C select
    initial begin
        for (k = 0; k < 64; k = k + 1) dtab[k] = (k < 32) ? dclass(k[4:0]) : cclass(k[2:1], k[0]);
    end
    reg  [W-1:0] dq;
    always @(posedge clk) begin
        dq <= (rst || !h3) ? {W{1'b0}} : dtab[{1'b0, d3}];
        cq <= dtab[{3'b100, c2, n2}][2:0];
    end
    assign fin = dq[DQ_FIN];
    assign mo  = dq[DQ_IQ];
    assign prod = p_r[PW-1:0];

    // ---------------- stage 4: window, saturation, write-back ----------------
    /* verilator lint_off UNUSEDSIGNAL */  // p_r[SH-1:0] is below the output window
    wire [W-1:0] r_win = p_r[SH+W-1:SH];
    wire         p_neg = p_r[AW-1];
    /* verilator lint_on UNUSEDSIGNAL */
    // the window is out of range iff bits AW-1 .. SH+W-1 are not all equal
    wire         ovf    = ~(&p_r[AW-1:SH+W-1] | ~|p_r[AW-1:SH+W-1]);
    wire         is_cmp = dq[DQ_CMP];
    wire         clamp  = is_cmp && (r_win > HPW);                     // compare values are >= 0
    assign       y      = ovf ? {p_neg, {(W-1){~p_neg}}} : clamp ? HPW : r_win;
    reg  [W-1:0]  id_st;
    reg  [CW-1:0] ca_st, cb_st;
    reg           sat_acc;

    always @(posedge clk) begin
        if (dq[DQ_WA]) rf_a[dq[DQ_AD +: 4]] <= y;
        if (dq[DQ_WB]) rf_b[{2'b00, dq[DQ_AD +: 2]}] <= y;
    end

    always @(posedge clk) begin
        if (rst) begin
            sel_m1 <= A_PB[3:0]; sel_m <= A_PC[3:0];
            id_st <= {W{1'b0}}; ca_st <= {CW{1'b0}}; cb_st <= {CW{1'b0}};
            i_d <= {W{1'b0}}; i_q <= {W{1'b0}};
            cmp_a <= {CW{1'b0}}; cmp_b <= {CW{1'b0}}; cmp_c <= {CW{1'b0}};
            sat_acc <= 1'b0; sat <= 1'b0; done <= 1'b0;
        end else begin
            done <= fin;
            sat  <= fin && (sat_acc || ovf || clamp);
            if (acc_front || acc_mod)
                sat_acc <= 1'b0;
            else if (dq[DQ_SACC])
                sat_acc <= sat_acc || ovf || clamp;
            if (dq[DQ_F1]) sel_m1 <= p_neg ? A_UA[3:0] : A_PB[3:0];   // u_A < u_B
            if (dq[DQ_F2]) sel_m  <= p_neg ? sel_m1 : A_PC[3:0];      // min(u_A, u_B) < u_C
            if (dq[DQ_ID]) id_st <= y;
            if (dq[DQ_IQ]) begin
                i_d <= id_st;
                i_q <= y;
            end
            if (dq[DQ_CA]) ca_st <= y[CW-1:0];
            if (dq[DQ_CB]) cb_st <= y[CW-1:0];
            if (dq[DQ_CC]) begin
                cmp_a <= ca_st;
                cmp_b <= cb_st;
                cmp_c <= y[CW-1:0];
            end
        end
    end
endmodule
`default_nettype wire
