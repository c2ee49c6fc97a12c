// seq_lockstep_tb: two implementations of the sequencer and the status/counter memory in lockstep
// (tb/test_seq_lockstep.py; not in sim_files.f: the test generates the two wrappers).
//
// pair_old and pair_new (generated) take the same inputs (everything ctrl_seq and the status block
// see) and expose `obs`: every ctrl_seq output other than the status stream, the status block's
// CPU read data and its memory write port (enable, word, data).  Each clock the two must be
// identical; the inputs are random (xorshift64*, seed SEED): PWM periods of several lengths and
// random triggers, ADC samples late or spurious, core updates after random latencies (and
// spurious ones), ref_ok gaps, register changes, CPU reads (at most every other clock, as
// emc_bus issues them), counter clears, events, resets; every STUFF_EVERY clocks the counter
// words of both memories are set to the same values near 2^32 - 1 so that the sweeps saturate.
// Prints one line: cycles, activity counts and the number of mismatching clocks.
`default_nettype none
`include "empc_regs.vh"
module seq_lockstep_tb;
    parameter integer N = 4;
    parameter integer CYCLES = 200000;
    parameter integer SEED = 1;
    parameter integer STUFF_EVERY = 150000;
    localparam integer OBS_W = 1024;
    reg clk = 1'b0;
    always #5 clk = ~clk;

    reg         rst, adc_trig, period_start, run, adc_valid, task_pos, ref_ok, ref_q, core_done;
    reg  [7:0]  ppc;
    reg  [15:0] theta;
    reg  [31:0] pos;
    reg  signed [12:0] cur0, cur1, cur2;
    reg  [17:0] kdc;
    reg  signed [17:0] kacc, id_ref, iq_ref;
    reg  [4:0]  kacc_shift;
    reg  [47:0] core_u;
    reg  [95:0] core_ebar;
    reg  [10:0] core_flags;
    reg         reg_rd, cnt_clear, adc_sat, cmp_clip;
    reg  [7:0]  reg_addr;
    wire [OBS_W-1:0] obs_o, obs_n;
    wire        core_start;

    pair_old #(.N(N)) u_o (.clk(clk), .rst(rst), .adc_trig(adc_trig), .period_start(period_start), .ppc(ppc),
        .run(run), .theta(theta), .pos(pos), .adc_valid(adc_valid), .cur0(cur0), .cur1(cur1), .cur2(cur2), .kdc(kdc),
        .kacc(kacc), .kacc_shift(kacc_shift), .id_ref(id_ref), .iq_ref(iq_ref), .task_pos(task_pos), .ref_ok(ref_ok),
        .ref_q(ref_q), .core_done(core_done), .core_u(core_u), .core_ebar(core_ebar), .core_flags(core_flags),
        .reg_rd(reg_rd), .reg_addr(reg_addr), .cnt_clear(cnt_clear), .adc_sat(adc_sat), .cmp_clip(cmp_clip),
        .obs(obs_o), .core_start(core_start));
    /* verilator lint_off PINCONNECTEMPTY */
    pair_new #(.N(N)) u_n (.clk(clk), .rst(rst), .adc_trig(adc_trig), .period_start(period_start), .ppc(ppc),
        .run(run), .theta(theta), .pos(pos), .adc_valid(adc_valid), .cur0(cur0), .cur1(cur1), .cur2(cur2), .kdc(kdc),
        .kacc(kacc), .kacc_shift(kacc_shift), .id_ref(id_ref), .iq_ref(iq_ref), .task_pos(task_pos), .ref_ok(ref_ok),
        .ref_q(ref_q), .core_done(core_done), .core_u(core_u), .core_ebar(core_ebar), .core_flags(core_flags),
        .reg_rd(reg_rd), .reg_addr(reg_addr), .cnt_clear(cnt_clear), .adc_sat(adc_sat), .cmp_clip(cmp_clip),
        .obs(obs_n), .core_start());
    /* verilator lint_on PINCONNECTEMPTY */

    reg  [63:0] prng;                            // xorshift64*: the same sequence in every simulator
    function [31:0] r32(input integer unused_arg);
        begin
            prng = prng ^ (prng >> 12);
            prng = prng ^ (prng << 25);
            prng = prng ^ (prng >> 27);
            r32 = (prng * 64'h2545F4914F6CDD1D) >> 32;
        end
    endfunction
    function integer rnd(input integer n);       // 0 .. n-1
        rnd = r32(0) % n;
    endfunction

    integer cyc, per_len, ph, core_cnt, adc_cnt, rd_gap, mode, rst_cnt, ref_low, b, a;
    integer mism, n_trig, n_load, n_core, n_clear, n_rst, n_rd, n_rdnz, n_stuff;
    reg  [31:0] stuff;
    initial begin
        prng = 64'h9E3779B97F4A7C15 ^ SEED;
        mism = 0; n_trig = 0; n_load = 0; n_core = 0; n_clear = 0; n_rst = 0; n_rd = 0; n_rdnz = 0; n_stuff = 0;
        rst = 1'b1; rst_cnt = 6; adc_trig = 0; period_start = 0; run = 1; adc_valid = 0; task_pos = 0; ref_ok = 1;
        ref_q = 0; core_done = 0; ppc = 1; theta = 0; pos = 0; cur0 = 0; cur1 = 0; cur2 = 0; kdc = 18'h10000;
        kacc = 0; kacc_shift = 0; id_ref = 0; iq_ref = 0; core_u = 0; core_ebar = 0; core_flags = 0; reg_rd = 0;
        reg_addr = 0; cnt_clear = 0; adc_sat = 0; cmp_clip = 0; per_len = 1000; ph = 0; core_cnt = 0; adc_cnt = 0;
        rd_gap = 0; mode = 0; ref_low = 0;
        for (cyc = 0; cyc < CYCLES; cyc = cyc + 1) begin
            @(negedge clk);
            if (obs_o !== obs_n) begin
                mism = mism + 1;
                if (mism <= 10) $display("MISMATCH cycle %0d: old ^ new = %h", cyc, obs_o ^ obs_n);
            end
            n_load = n_load + {31'd0, obs_o[0]};
            if (reg_rd && obs_o[1]) n_rdnz = n_rdnz + 1;
            // ---- counters near saturation, the same in both memories ----
            if (cyc % STUFF_EVERY == STUFF_EVERY - 1) begin
                n_stuff = n_stuff + 1;
                for (a = 32; a < 64; a = a + 1) begin
                    stuff = 32'hFFFFFFFF - rnd(3);
                    for (b = 0; b < 32; b = b + 1) begin
                        u_o.smem[a * 32 + b] = stuff[b];
                        u_n.u_status.smem[a * 32 + b] = stuff[b];
                    end
                end
            end
            // ---- reset ----
            if (rst_cnt > 0) begin rst = 1'b1; rst_cnt = rst_cnt - 1; end
            else begin rst = 1'b0; if (rnd(200000) == 0) begin rst_cnt = 1 + rnd(6); n_rst = n_rst + 1; end end
            // ---- PWM periods ----
            if (cyc % 25000 == 0) begin
                mode = rnd(4);           // 0..2: regular periods, 3: random triggers
                case (rnd(5))
                    0: per_len = 300; 1: per_len = 700; 2: per_len = 1500; 3: per_len = 5000;
                    default: per_len = 200 + rnd(3000);
                endcase
            end
            if (mode < 3) begin
                ph = (ph + 1 >= per_len) ? 0 : ph + 1;
                period_start = (ph == 0);
                adc_trig = (ph == per_len / 2);
            end else begin
                period_start = (rnd(800) == 0);
                adc_trig = (rnd(700) == 0);
            end
            if (adc_trig) begin n_trig = n_trig + 1; adc_cnt = 1 + rnd(160); end
            adc_valid = 1'b0;
            if (adc_cnt > 0) begin adc_cnt = adc_cnt - 1; adc_valid = (adc_cnt == 0); end
            if (rnd(5000) == 0) adc_valid = 1'b1;
            // ---- core ----
            core_done = 1'b0;
            if (core_start) core_cnt = 2 + rnd(150);
            else if (core_cnt > 0) begin
                core_cnt = core_cnt - 1;
                if (core_cnt == 0) core_done = 1'b1;
            end
            if (rnd(30000) == 0) core_done = 1'b1;
            if (core_done) begin
                n_core = n_core + 1;
                core_u = {r32(0), r32(0)};
                core_ebar = {r32(0), r32(0), r32(0)};
                core_flags = (rnd(3) == 0) ? r32(0) : 11'd0;
            end
            // ---- references, measurements ----
            if (ref_low > 0) begin ref_low = ref_low - 1; ref_ok = (ref_low == 0); end
            else if (rnd(3000) == 0) begin ref_low = 1 + rnd(400); ref_ok = 1'b0; end
            ref_q = r32(0);
            if (rnd(2) == 0) theta = r32(0);
            if (rnd(3) == 0) pos = (rnd(4) == 0) ? r32(0) : pos + rnd(600) - 300;
            cur0 = r32(0); cur1 = r32(0); cur2 = r32(0);
            // ---- registers ----
            if (rnd(4000) == 0) run = ~run;
            if (rnd(20000) == 0) task_pos = ~task_pos;
            if (rnd(20000) == 0) ppc = rnd(7);
            if (rnd(3000) == 0) begin
                kdc = r32(0); kacc = r32(0); kacc_shift = r32(0); id_ref = r32(0); iq_ref = r32(0);
            end
            // ---- CPU reads (status and counter words mostly), counter clears, events ----
            reg_rd = 1'b0;
            if (rd_gap > 0) rd_gap = rd_gap - 1;
            else if (rnd(4) == 0) begin
                reg_rd = 1'b1; rd_gap = 1 + rnd(3); n_rd = n_rd + 1;
                reg_addr = (rnd(4) != 0) ? 8'h20 + rnd(32) : rnd(256);
            end
            cnt_clear = (rnd(6000) == 0);
            n_clear = n_clear + (cnt_clear ? 1 : 0);
            adc_sat = (rnd(3000) == 0);
            cmp_clip = (rnd(3000) == 0);
        end
        $display("lockstep N=%0d seed=%0d: %0d cycles, %0d triggers, %0d cmp_load, %0d core updates, %0d resets, %0d counter clears, %0d reads (%0d non-zero), %0d counter stuffings: %0d mismatches",
                 N, SEED, CYCLES, n_trig, n_load, n_core, n_rst, n_clear, n_rd, n_rdnz, n_stuff, mism);
        $finish;
    end
endmodule
`default_nettype wire
