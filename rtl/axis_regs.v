// Generated from gen/empc/regmap.py by gen/empc/regblock.py (python -m empc.regmap --all). Do not edit.
//
// axis_regs: registers of one axis (mpc_axis).
//
// Write decode, stored registers with their reset values, command pulses, W1C bits and
// the read path of the registers of this block in gen/empc/regmap.py (what each register
// is and the rules: gen/empc/regblock.py, docs/registers.md).  Ports: a stored register
// or field is an output named after it, a read-only value an input of the same name.
// Read path: gated copies (0 unless read) ORed.
// Parameters: none (build-dependent reset values are empc_formats.vh macros).
// Latency: writes act in the clock after reg_wr (window strobes: combinational);
// reg_rdata is valid the clock after reg_rd and 0 in every other clock.
// Reset: synchronous (rst); stored registers to the map's reset values, pulses and read
// data to 0.
`default_nettype none
`include "empc_formats.vh"
module axis_regs (
    input  wire         clk,
    input  wire         rst,
    input  wire         reg_wr,               // write strobe (1 clock) for a word of this block
    input  wire         reg_rd,               // read strobe (1 clock)
    input  wire [7:0]   reg_addr,             // word offset in the block
    input  wire [31:0]  reg_wdata,
    output wire [31:0]  reg_rdata,            // read data, the clock after reg_rd (0 otherwise)
    output wire [294:0] rd_vals,              // every readable value but the shadowed registers, packed (combinational; the shared read path axis_rd)
    output wire [16:0]  sh_we,                // accepted write of a shadowed register (combinational), one-hot: FAULT_MASK, DEAD_TIME, KDC, UDC, UDC_MIN, UDC_MAX, OC_THRESH, ANGLE_CAL, HALL_OFFSET, KACC, ID_REF, IQ_REF, SEG_ADDR, FW, FW_R2, IQ_HOLD, ADC_SUM_THRESH
    output reg          ctrl_enable,          // CTRL.enable (RW)
    output reg          ctrl_run,             // CTRL.run (RW)
    output reg  [7:0]   ctrl_pwm_per_control, // CTRL.pwm_per_control (RW)
    output reg          cmd_fault_clear,      // CMD.fault_clear: pulse
    output reg          cmd_adc_cal,          // CMD.adc_cal: pulse
    output reg          cmd_ref_sync,         // CMD.ref_sync: pulse
    output reg          cmd_coef_swap,        // CMD.coef_swap: pulse
    output reg          cmd_clear_counters,   // CMD.clear_counters: pulse
    output reg          cmd_align_clear,      // CMD.align_clear: pulse
    input  wire         status_running,       // STATUS.running value
    input  wire         status_bridges_on,    // STATUS.bridges_on value
    input  wire         status_aligned,       // STATUS.aligned value
    input  wire         status_adc_cal_busy,  // STATUS.adc_cal_busy value
    input  wire         status_adc_cal_done,  // STATUS.adc_cal_done value
    input  wire         status_core_ready,    // STATUS.core_ready value
    input  wire         status_coef_bank,     // STATUS.coef_bank value
    input  wire         status_swap_pending,  // STATUS.swap_pending value
    input  wire         status_fault,         // STATUS.fault value
    input  wire         status_coef_valid,    // STATUS.coef_valid value
    input  wire         status_swap_refused,  // STATUS.swap_refused value
    input  wire         status_adc_refused,   // STATUS.adc_refused value
    input  wire         status_wr_refused,    // STATUS.wr_refused value
    input  wire         fault_overcurrent,    // FAULT.overcurrent value
    input  wire         fault_hall,           // FAULT.hall value
    input  wire         fault_encoder,        // FAULT.encoder value
    input  wire         fault_watchdog,       // FAULT.watchdog value
    input  wire         fault_dclink,         // FAULT.dclink value
    input  wire         fault_overrun,        // FAULT.overrun value
    input  wire         fault_adc,            // FAULT.adc value
    input  wire         fault_pstage,         // FAULT.pstage value
    input  wire         fault_clock,          // FAULT.clock value
    input  wire         fault_coef,           // FAULT.coef value
    input  wire         fault_hall_enc,       // FAULT.hall_enc value
    input  wire         fault_enc_break,      // FAULT.enc_break value
    input  wire         fault_adc_stuck,      // FAULT.adc_stuck value
    input  wire         fault_adc_sum,        // FAULT.adc_sum value
    input  wire         fault_adc_frozen,     // FAULT.adc_frozen value
    output reg  [14:0]  fault_mask,           // FAULT_MASK (RW)
    output reg  [7:0]   dead_time,            // DEAD_TIME (RW)
    output reg  [17:0]  kdc,                  // KDC (RW)
    output reg  [19:0]  udc,                  // UDC (RW)
    output reg          udc_wr,               // UDC: pulse when a write is accepted
    output reg  [19:0]  udc_min,              // UDC_MIN (RW)
    output reg  [19:0]  udc_max,              // UDC_MAX (RW)
    output reg  [11:0]  oc_thresh,            // OC_THRESH (RW)
    output reg  [2:0]   adc_off_we,           // write pulse, one-hot: ADC_OFF0, ADC_OFF1, ADC_OFF2
    output reg  [11:0]  adc_off_wdata,        // written value
    input  wire [11:0]  adc_off0,             // ADC_OFF0 value
    input  wire [11:0]  adc_off1,             // ADC_OFF1 value
    input  wire [11:0]  adc_off2,             // ADC_OFF2 value
    output reg  [15:0]  angle_cal,            // ANGLE_CAL (RW)
    output reg  [15:0]  hall_offset,          // HALL_OFFSET (RW)
    output reg  [17:0]  kacc,                 // KACC.kacc (RW)
    output reg  [3:0]   kacc_load_shift,      // KACC.load_shift (RW)
    output reg  [4:0]   kacc_shift,           // KACC.shift (RW)
    output reg  [2:0]   kacc_win,             // KACC.win (RW)
    output reg  signed [17:0]  id_ref,        // ID_REF (RW)
    output reg  signed [17:0]  iq_ref,        // IQ_REF (RW)
    output reg  [3:0]   seg_addr,             // SEG_ADDR (RW)
    output wire         seg_we,               // write of a word of window seg (combinational)
    output wire         seg_re,               // read of a word of window seg (combinational)
    output wire [2:0]   seg_idx,              // word index in the window (SEG_LEN = 0)
    output reg          seg_start,            // SEG_START: pulse
    output reg  [3:0]   seg_start_data,       // SEG_START: written value
    output wire         gov_we,               // write of a word of window gov (combinational)
    output wire         gov_re,               // read of a word of window gov (combinational)
    output reg  [7:0]   fw_nmax,              // FW.nmax (RW)
    output reg  [15:0]  fw_r2_hi,             // FW_R2.hi (RW)
    output reg  [15:0]  fw_r2_lo,             // FW_R2.lo (RW)
    output reg  [11:0]  iq_hold,              // IQ_HOLD (RW)
    input  wire [31:0]  pos,                  // POS value
    output wire         stat_re,              // read of a word of window stat (combinational)
    input  wire [15:0]  theta,                // THETA value
    input  wire [11:0]  iabc0_a,              // IABC0.a value
    input  wire [11:0]  iabc0_b,              // IABC0.b value
    input  wire [11:0]  iabc1,                // IABC1 value
    input  wire [15:0]  latency,              // LATENCY value
    output wire         cnt_re,               // read of a word of window cnt (combinational)
    input  wire [19:0]  adc_psum0_sum,        // ADC_PSUM0.sum value
    input  wire [6:0]   adc_psum0_count,      // ADC_PSUM0.count value
    input  wire [19:0]  adc_psum1_sum,        // ADC_PSUM1.sum value
    input  wire [6:0]   adc_psum1_count,      // ADC_PSUM1.count value
    input  wire [19:0]  adc_psum2_sum,        // ADC_PSUM2.sum value
    input  wire [6:0]   adc_psum2_count,      // ADC_PSUM2.count value
    input  wire [7:0]   cnt_wr_refused,       // CNT_WR_REFUSED value
    input  wire [7:0]   cnt_adc_miss,         // CNT_ADC_MISS value
    input  wire [15:0]  cnt_enc_err,          // CNT_ENC_ERR value
    output reg  [11:0]  adc_sum_thresh,       // ADC_SUM_THRESH (RW)
    input  wire [7:0]   cnt_swap_ref,         // CNT_SWAP_REF value
    input  wire [31:0]  seg_rdata,            // window read data (0 unless read)
    input  wire [31:0]  smem_rdata,           // window read data (0 unless read)
    input  wire         bridges_live,         // guard: writes to its registers are refused while high
    input  wire         unlock_tick,          // timebase of the UNLOCK unlock (pulses)
    output wire [1:0]   unlock_armed,         // UNLOCK unlock: ticks left, 0 = not armed (status, proofs)
    output reg          wr_refused            // pulse: a write was refused (guard, unlock or illegal value)
);
    // legal values of CTRL.pwm_per_control as a table (one LUT, no compares)
    localparam [255:0] LEGAL_CTRL_PWM_PER_CONTROL = 256'hfffffffffffffffffffffffffffffffffffffffffffffffffffffffffffffffe;
    // legal values of DEAD_TIME as a table (one LUT, no compares)
    localparam [255:0] LEGAL_DEAD_TIME = 256'hfffffffffffffffffffffffffffffffffffffffffffffffffffffffffff00000;

    // ---------------- windows: address tables (one LUT level, no magnitude compares)
    localparam [255:0] SEG_WORDS = 256'h0000000000000000000000000000000000000000000000000000000007f00000;
    wire seg_sel = SEG_WORDS[reg_addr];
    assign seg_we = reg_wr && seg_sel;
    assign seg_re = reg_rd && seg_sel;
    assign seg_idx = reg_addr[2:0] - 3'd4;   // word - SEG_LEN
    localparam [255:0] GOV_WORDS = 256'h0000000000000000000000000000000000000000000000000000000010000000;
    wire gov_sel = GOV_WORDS[reg_addr];
    assign gov_we = reg_wr && gov_sel;
    assign gov_re = reg_rd && gov_sel;
    localparam [255:0] STAT_WORDS = 256'h000000000000000000000000000000000000000000000000000000fa00000000;
    wire stat_sel = STAT_WORDS[reg_addr];
    assign stat_re = reg_rd && stat_sel;
    localparam [255:0] CNT_WORDS = 256'h0000000000000000000000000000000000000000000000009fff080000000000;
    wire cnt_sel = CNT_WORDS[reg_addr];
    assign cnt_re = reg_rd && cnt_sel;

    // ---------------- write decode: one predecode per page, a case on the low bits
    wire wr_p0 = reg_wr && (reg_addr[7:7] == 1'd0);
    // unlock: UNLOCK armed with its key until the 2th unlock_tick; the next write of the block consumes it
    reg  [1:0] unl_cnt;
    wire unl = |unl_cnt;
    assign unlock_armed = unl_cnt;
    always @(posedge clk) begin
        cmd_fault_clear <= 1'd0;
        cmd_adc_cal <= 1'd0;
        cmd_ref_sync <= 1'd0;
        cmd_coef_swap <= 1'd0;
        cmd_clear_counters <= 1'd0;
        cmd_align_clear <= 1'd0;
        seg_start <= 1'b0;
        udc_wr <= 1'b0;
        adc_off_we <= 3'd0;
        wr_refused <= 1'b0;
        if (rst) begin
            ctrl_enable <= 1'd0;
            ctrl_run <= 1'd0;
            ctrl_pwm_per_control <= `EMPC_PWM_PER_CONTROL;
            fault_mask <= 15'h7fff;
            dead_time <= 8'd50;
            kdc <= 18'h10000;
            udc <= 20'd0;
            udc_min <= 20'd10000;
            udc_max <= 20'd60000;
            oc_thresh <= 12'd1800;
            angle_cal <= 16'd0;
            hall_offset <= 16'd0;
            kacc <= `EMPC_KACC;
            kacc_load_shift <= `EMPC_KACC_LOAD_SHIFT;
            kacc_shift <= `EMPC_KACC_SHIFT;
            kacc_win <= `EMPC_KACC_WIN;
            id_ref <= 18'd0;
            iq_ref <= 18'd0;
            seg_addr <= 4'd0;
            seg_start_data <= 4'd0;
            fw_nmax <= `EMPC_FW_NMAX;
            fw_r2_hi <= `EMPC_FW_R2_HI;
            fw_r2_lo <= `EMPC_FW_R2_LO;
            iq_hold <= `EMPC_IQ_HOLD;
            adc_sum_thresh <= 12'd300;
            adc_off_wdata <= 12'd0;
            unl_cnt <= 2'd0;
        end else begin
            if (reg_wr) unl_cnt <= 2'd0;   // consumed by any write
            else if (unl && unlock_tick) unl_cnt <= unl_cnt - 1'b1;
            if (wr_p0) begin
                case (reg_addr[6:0])
                    7'h0: begin   // CTRL
                        if (LEGAL_CTRL_PWM_PER_CONTROL[reg_wdata[15:8]] && (!bridges_live || reg_wdata[15:8] == ctrl_pwm_per_control)) begin
                            ctrl_enable <= reg_wdata[0];
                            ctrl_run <= reg_wdata[1];
                            ctrl_pwm_per_control <= reg_wdata[15:8];
                        end else begin
                            wr_refused <= 1'b1;
                            if (reg_wdata[0] == 1'd0) ctrl_enable <= 1'd0;
                            if (reg_wdata[1] == 1'd0) ctrl_run <= 1'd0;
                        end
                    end
                    7'h1: begin   // CMD
                        if ((!bridges_live || reg_wdata[1] == 1'd0)) begin
                            cmd_fault_clear <= reg_wdata[0];
                            cmd_adc_cal <= reg_wdata[1];
                            cmd_ref_sync <= reg_wdata[2];
                            cmd_coef_swap <= reg_wdata[3];
                            cmd_clear_counters <= reg_wdata[4];
                            cmd_align_clear <= reg_wdata[5];
                        end else begin
                            wr_refused <= 1'b1;
                        end
                    end
                    7'h4: begin   // FAULT_MASK
                        if (!bridges_live && unl) begin
                            fault_mask <= reg_wdata[14:0];
                        end else begin
                            wr_refused <= 1'b1;
                        end
                    end
                    7'h5: begin   // DEAD_TIME
                        if (!bridges_live && LEGAL_DEAD_TIME[reg_wdata[7:0]]) begin
                            dead_time <= reg_wdata[7:0];
                        end else begin
                            wr_refused <= 1'b1;
                        end
                    end
                    7'h6: begin   // KDC
                        kdc <= reg_wdata[17:0];
                    end
                    7'h7: begin   // UDC
                        udc <= reg_wdata[19:0];
                        udc_wr <= 1'b1;
                    end
                    7'h8: begin   // UDC_MIN
                        if (!bridges_live && (reg_wdata[19:0] >= 20'd1) && (reg_wdata[19:0] <= 20'd1048574)) begin
                            udc_min <= reg_wdata[19:0];
                        end else begin
                            wr_refused <= 1'b1;
                        end
                    end
                    7'h9: begin   // UDC_MAX
                        if (!bridges_live && (reg_wdata[19:0] >= 20'd1) && (reg_wdata[19:0] <= 20'd1048574)) begin
                            udc_max <= reg_wdata[19:0];
                        end else begin
                            wr_refused <= 1'b1;
                        end
                    end
                    7'ha: begin   // OC_THRESH
                        if (!bridges_live && (reg_wdata[11:0] >= 12'd1) && (reg_wdata[11:0] <= 12'd1900)) begin
                            oc_thresh <= reg_wdata[11:0];
                        end else begin
                            wr_refused <= 1'b1;
                        end
                    end
                    7'hb: begin   // ADC_OFF0
                        if (!bridges_live && (reg_wdata[11:0] >= 12'd1901) && (reg_wdata[11:0] <= 12'd2194)) begin
                            adc_off_we <= 3'b001;
                            adc_off_wdata <= reg_wdata[11:0];
                        end else begin
                            wr_refused <= 1'b1;
                        end
                    end
                    7'hc: begin   // ADC_OFF1
                        if (!bridges_live && (reg_wdata[11:0] >= 12'd1901) && (reg_wdata[11:0] <= 12'd2194)) begin
                            adc_off_we <= 3'b010;
                            adc_off_wdata <= reg_wdata[11:0];
                        end else begin
                            wr_refused <= 1'b1;
                        end
                    end
                    7'hd: begin   // ADC_OFF2
                        if (!bridges_live && (reg_wdata[11:0] >= 12'd1901) && (reg_wdata[11:0] <= 12'd2194)) begin
                            adc_off_we <= 3'b100;
                            adc_off_wdata <= reg_wdata[11:0];
                        end else begin
                            wr_refused <= 1'b1;
                        end
                    end
                    7'he: begin   // ANGLE_CAL
                        if (!bridges_live) begin
                            angle_cal <= reg_wdata[15:0];
                        end else begin
                            wr_refused <= 1'b1;
                        end
                    end
                    7'hf: begin   // HALL_OFFSET
                        if (!bridges_live) begin
                            hall_offset <= reg_wdata[15:0];
                        end else begin
                            wr_refused <= 1'b1;
                        end
                    end
                    7'h10: begin   // KACC
                        kacc <= reg_wdata[17:0];
                        kacc_load_shift <= reg_wdata[21:18];
                        kacc_shift <= reg_wdata[28:24];
                        kacc_win <= reg_wdata[31:29];
                    end
                    7'h11: begin   // ID_REF
                        id_ref <= reg_wdata[17:0];
                    end
                    7'h12: begin   // IQ_REF
                        iq_ref <= reg_wdata[17:0];
                    end
                    7'h13: begin   // SEG_ADDR
                        seg_addr <= reg_wdata[3:0];
                    end
                    7'h1b: begin   // SEG_START
                        seg_start <= 1'b1;
                        seg_start_data <= reg_wdata[3:0];
                    end
                    7'h1d: begin   // FW
                        fw_nmax <= reg_wdata[7:0];
                    end
                    7'h1e: begin   // FW_R2
                        fw_r2_hi <= reg_wdata[15:0];
                        fw_r2_lo <= reg_wdata[31:16];
                    end
                    7'h1f: begin   // IQ_HOLD
                        iq_hold <= reg_wdata[11:0];
                    end
                    7'h40: begin   // ADC_SUM_THRESH
                        if (!bridges_live && (reg_wdata[11:0] >= 12'd1) && (reg_wdata[11:0] <= 12'd1900)) begin
                            adc_sum_thresh <= reg_wdata[11:0];
                        end else begin
                            wr_refused <= 1'b1;
                        end
                    end
                    7'h41: begin   // UNLOCK
                        if (reg_wdata[15:0] == 16'd49374) unl_cnt <= 2'd2;
                        else wr_refused <= 1'b1;
                    end
                    default: ;
                endcase
            end
        end
    end

    // ---------------- read path: gated copies / shared read register, ORed
    wire rd_p0 = reg_rd && (reg_addr[7:7] == 1'd0);
    reg  [9:0]   q_ctrl;
    reg  [12:0]  q_status;
    reg  [14:0]  q_fault;
    reg  [14:0]  q_fault_mask;
    reg  [7:0]   q_dead_time;
    reg  [17:0]  q_kdc;
    reg  [19:0]  q_udc;
    reg  [19:0]  q_udc_min;
    reg  [19:0]  q_udc_max;
    reg  [11:0]  q_oc_thresh;
    reg  [11:0]  q_adc_off0;
    reg  [11:0]  q_adc_off1;
    reg  [11:0]  q_adc_off2;
    reg  [15:0]  q_angle_cal;
    reg  [15:0]  q_hall_offset;
    reg  [29:0]  q_kacc;
    reg  [17:0]  q_id_ref;
    reg  [17:0]  q_iq_ref;
    reg  [3:0]   q_seg_addr;
    reg  [7:0]   q_fw;
    reg  [31:0]  q_fw_r2;
    reg  [11:0]  q_iq_hold;
    reg  [31:0]  q_pos;
    reg  [15:0]  q_theta;
    reg  [23:0]  q_iabc0;
    reg  [11:0]  q_iabc1;
    reg  [15:0]  q_latency;
    reg  [26:0]  q_adc_psum0;
    reg  [26:0]  q_adc_psum1;
    reg  [26:0]  q_adc_psum2;
    reg  [7:0]   q_cnt_wr_refused;
    reg  [7:0]   q_cnt_adc_miss;
    reg  [15:0]  q_cnt_enc_err;
    reg  [11:0]  q_adc_sum_thresh;
    reg  [7:0]   q_cnt_swap_ref;
    always @(posedge clk) begin
        q_ctrl <= (rd_p0 && reg_addr[6:0] == 7'h0) ? {ctrl_pwm_per_control, ctrl_run, ctrl_enable} : 10'd0;
        q_status <= (rd_p0 && reg_addr[6:0] == 7'h2) ? {status_wr_refused, status_adc_refused,
            status_swap_refused, status_coef_valid, status_fault, status_swap_pending, status_coef_bank,
            status_core_ready, status_adc_cal_done, status_adc_cal_busy, status_aligned, status_bridges_on,
            status_running} : 13'd0;
        q_fault <= (rd_p0 && reg_addr[6:0] == 7'h3) ? {fault_adc_frozen, fault_adc_sum, fault_adc_stuck,
            fault_enc_break, fault_hall_enc, fault_coef, fault_clock, fault_pstage, fault_adc, fault_overrun,
            fault_dclink, fault_watchdog, fault_encoder, fault_hall, fault_overcurrent} : 15'd0;
        q_fault_mask <= (rd_p0 && reg_addr[6:0] == 7'h4) ? fault_mask : 15'd0;
        q_dead_time <= (rd_p0 && reg_addr[6:0] == 7'h5) ? dead_time : 8'd0;
        q_kdc <= (rd_p0 && reg_addr[6:0] == 7'h6) ? kdc : 18'd0;
        q_udc <= (rd_p0 && reg_addr[6:0] == 7'h7) ? udc : 20'd0;
        q_udc_min <= (rd_p0 && reg_addr[6:0] == 7'h8) ? udc_min : 20'd0;
        q_udc_max <= (rd_p0 && reg_addr[6:0] == 7'h9) ? udc_max : 20'd0;
        q_oc_thresh <= (rd_p0 && reg_addr[6:0] == 7'ha) ? oc_thresh : 12'd0;
        q_adc_off0 <= (rd_p0 && reg_addr[6:0] == 7'hb) ? adc_off0 : 12'd0;
        q_adc_off1 <= (rd_p0 && reg_addr[6:0] == 7'hc) ? adc_off1 : 12'd0;
        q_adc_off2 <= (rd_p0 && reg_addr[6:0] == 7'hd) ? adc_off2 : 12'd0;
        q_angle_cal <= (rd_p0 && reg_addr[6:0] == 7'he) ? angle_cal : 16'd0;
        q_hall_offset <= (rd_p0 && reg_addr[6:0] == 7'hf) ? hall_offset : 16'd0;
        q_kacc <= (rd_p0 && reg_addr[6:0] == 7'h10) ? {kacc_win, kacc_shift, kacc_load_shift, kacc} : 30'd0;
        q_id_ref <= (rd_p0 && reg_addr[6:0] == 7'h11) ? id_ref : 18'd0;
        q_iq_ref <= (rd_p0 && reg_addr[6:0] == 7'h12) ? iq_ref : 18'd0;
        q_seg_addr <= (rd_p0 && reg_addr[6:0] == 7'h13) ? seg_addr : 4'd0;
        q_fw <= (rd_p0 && reg_addr[6:0] == 7'h1d) ? fw_nmax : 8'd0;
        q_fw_r2 <= (rd_p0 && reg_addr[6:0] == 7'h1e) ? {fw_r2_lo, fw_r2_hi} : 32'd0;
        q_iq_hold <= (rd_p0 && reg_addr[6:0] == 7'h1f) ? iq_hold : 12'd0;
        q_pos <= (rd_p0 && reg_addr[6:0] == 7'h20) ? pos : 32'd0;
        q_theta <= (rd_p0 && reg_addr[6:0] == 7'h22) ? theta : 16'd0;
        q_iabc0 <= (rd_p0 && reg_addr[6:0] == 7'h28) ? {iabc0_b, iabc0_a} : 24'd0;
        q_iabc1 <= (rd_p0 && reg_addr[6:0] == 7'h29) ? iabc1 : 12'd0;
        q_latency <= (rd_p0 && reg_addr[6:0] == 7'h2a) ? latency : 16'd0;
        q_adc_psum0 <= (rd_p0 && reg_addr[6:0] == 7'h2c) ? {adc_psum0_count, adc_psum0_sum} : 27'd0;
        q_adc_psum1 <= (rd_p0 && reg_addr[6:0] == 7'h2d) ? {adc_psum1_count, adc_psum1_sum} : 27'd0;
        q_adc_psum2 <= (rd_p0 && reg_addr[6:0] == 7'h2e) ? {adc_psum2_count, adc_psum2_sum} : 27'd0;
        q_cnt_wr_refused <= (rd_p0 && reg_addr[6:0] == 7'h2f) ? cnt_wr_refused : 8'd0;
        q_cnt_adc_miss <= (rd_p0 && reg_addr[6:0] == 7'h3d) ? cnt_adc_miss : 8'd0;
        q_cnt_enc_err <= (rd_p0 && reg_addr[6:0] == 7'h3e) ? cnt_enc_err : 16'd0;
        q_adc_sum_thresh <= (rd_p0 && reg_addr[6:0] == 7'h40) ? adc_sum_thresh : 12'd0;
        q_cnt_swap_ref <= (rd_p0 && reg_addr[6:0] == 7'h42) ? cnt_swap_ref : 8'd0;
        if (rst) begin
            q_ctrl <= 10'd0;
            q_status <= 13'd0;
            q_fault <= 15'd0;
            q_fault_mask <= 15'd0;
            q_dead_time <= 8'd0;
            q_kdc <= 18'd0;
            q_udc <= 20'd0;
            q_udc_min <= 20'd0;
            q_udc_max <= 20'd0;
            q_oc_thresh <= 12'd0;
            q_adc_off0 <= 12'd0;
            q_adc_off1 <= 12'd0;
            q_adc_off2 <= 12'd0;
            q_angle_cal <= 16'd0;
            q_hall_offset <= 16'd0;
            q_kacc <= 30'd0;
            q_id_ref <= 18'd0;
            q_iq_ref <= 18'd0;
            q_seg_addr <= 4'd0;
            q_fw <= 8'd0;
            q_fw_r2 <= 32'd0;
            q_iq_hold <= 12'd0;
            q_pos <= 32'd0;
            q_theta <= 16'd0;
            q_iabc0 <= 24'd0;
            q_iabc1 <= 12'd0;
            q_latency <= 16'd0;
            q_adc_psum0 <= 27'd0;
            q_adc_psum1 <= 27'd0;
            q_adc_psum2 <= 27'd0;
            q_cnt_wr_refused <= 8'd0;
            q_cnt_adc_miss <= 8'd0;
            q_cnt_enc_err <= 16'd0;
            q_adc_sum_thresh <= 12'd0;
            q_cnt_swap_ref <= 8'd0;
        end
    end
    assign reg_rdata = seg_rdata
                     | smem_rdata
                     | {16'd0, q_ctrl[9:2], 6'd0, q_ctrl[1:0]}
                     | {19'd0, q_status}
                     | {17'd0, q_fault}
                     | {17'd0, q_fault_mask}
                     | {24'd0, q_dead_time}
                     | {14'd0, q_kdc}
                     | {12'd0, q_udc}
                     | {12'd0, q_udc_min}
                     | {12'd0, q_udc_max}
                     | {20'd0, q_oc_thresh}
                     | {20'd0, q_adc_off0}
                     | {20'd0, q_adc_off1}
                     | {20'd0, q_adc_off2}
                     | {16'd0, q_angle_cal}
                     | {16'd0, q_hall_offset}
                     | {q_kacc[29:22], 2'd0, q_kacc[21:0]}
                     | {{14{q_id_ref[17]}}, q_id_ref[17:0]}
                     | {{14{q_iq_ref[17]}}, q_iq_ref[17:0]}
                     | {28'd0, q_seg_addr}
                     | {24'd0, q_fw}
                     | q_fw_r2
                     | {20'd0, q_iq_hold}
                     | q_pos
                     | {16'd0, q_theta}
                     | {4'd0, q_iabc0[23:12], 4'd0, q_iabc0[11:0]}
                     | {20'd0, q_iabc1}
                     | {16'd0, q_latency}
                     | {1'd0, q_adc_psum0[26:20], 4'd0, q_adc_psum0[19:0]}
                     | {1'd0, q_adc_psum1[26:20], 4'd0, q_adc_psum1[19:0]}
                     | {1'd0, q_adc_psum2[26:20], 4'd0, q_adc_psum2[19:0]}
                     | {24'd0, q_cnt_wr_refused}
                     | {24'd0, q_cnt_adc_miss}
                     | {16'd0, q_cnt_enc_err}
                     | {20'd0, q_adc_sum_thresh}
                     | {24'd0, q_cnt_swap_ref};

    // ---------------- accepted writes of the registers axis_rd reads back from its write-through RAM
    // (the condition under which each register takes reg_wdata below)
    assign sh_we[0] = wr_p0 && reg_addr[6:0] == 7'h4 && !bridges_live && unl;   // FAULT_MASK
    assign sh_we[1] = wr_p0 && reg_addr[6:0] == 7'h5 && !bridges_live && LEGAL_DEAD_TIME[reg_wdata[7:0]];   // DEAD_TIME
    assign sh_we[2] = wr_p0 && reg_addr[6:0] == 7'h6;   // KDC
    assign sh_we[3] = wr_p0 && reg_addr[6:0] == 7'h7;   // UDC
    assign sh_we[4] = wr_p0 && reg_addr[6:0] == 7'h8 && !bridges_live && (reg_wdata[19:0] >= 20'd1) && (reg_wdata[19:0] <= 20'd1048574);   // UDC_MIN
    assign sh_we[5] = wr_p0 && reg_addr[6:0] == 7'h9 && !bridges_live && (reg_wdata[19:0] >= 20'd1) && (reg_wdata[19:0] <= 20'd1048574);   // UDC_MAX
    assign sh_we[6] = wr_p0 && reg_addr[6:0] == 7'ha && !bridges_live && (reg_wdata[11:0] >= 12'd1) && (reg_wdata[11:0] <= 12'd1900);   // OC_THRESH
    assign sh_we[7] = wr_p0 && reg_addr[6:0] == 7'he && !bridges_live;   // ANGLE_CAL
    assign sh_we[8] = wr_p0 && reg_addr[6:0] == 7'hf && !bridges_live;   // HALL_OFFSET
    assign sh_we[9] = wr_p0 && reg_addr[6:0] == 7'h10;   // KACC
    assign sh_we[10] = wr_p0 && reg_addr[6:0] == 7'h11;   // ID_REF
    assign sh_we[11] = wr_p0 && reg_addr[6:0] == 7'h12;   // IQ_REF
    assign sh_we[12] = wr_p0 && reg_addr[6:0] == 7'h13;   // SEG_ADDR
    assign sh_we[13] = wr_p0 && reg_addr[6:0] == 7'h1d;   // FW
    assign sh_we[14] = wr_p0 && reg_addr[6:0] == 7'h1e;   // FW_R2
    assign sh_we[15] = wr_p0 && reg_addr[6:0] == 7'h1f;   // IQ_HOLD
    assign sh_we[16] = wr_p0 && reg_addr[6:0] == 7'h40 && !bridges_live && (reg_wdata[11:0] >= 12'd1) && (reg_wdata[11:0] <= 12'd1900);   // ADC_SUM_THRESH

    // ---------------- every readable value for the shared read path (axis_rd), first register at bit 0
    assign rd_vals = {cnt_swap_ref, cnt_enc_err, cnt_adc_miss, cnt_wr_refused, {adc_psum2_count, adc_psum2_sum},
                      {adc_psum1_count, adc_psum1_sum}, {adc_psum0_count, adc_psum0_sum}, latency, iabc1,
                      {iabc0_b, iabc0_a}, theta, pos, adc_off2, adc_off1, adc_off0,
                      {fault_adc_frozen, fault_adc_sum, fault_adc_stuck, fault_enc_break, fault_hall_enc, fault_coef, fault_clock, fault_pstage, fault_adc, fault_overrun, fault_dclink, fault_watchdog, fault_encoder, fault_hall, fault_overcurrent},
                      {status_wr_refused, status_adc_refused, status_swap_refused, status_coef_valid, status_fault, status_swap_pending, status_coef_bank, status_core_ready, status_adc_cal_done, status_adc_cal_busy, status_aligned, status_bridges_on, status_running},
                      {ctrl_pwm_per_control, ctrl_run, ctrl_enable}};
endmodule
`default_nettype wire
