// Generated from gen/empc/regmap.py by gen/empc/regblock.py (python -m empc.regmap --all). Do not edit.
//
// axis_rd: the read path of NAXES axis_regs blocks (registers of one axis (mpc_axis)), shared.
//
// The CPU reads one axis at a time: the read registers of every axis live here instead of in
// every axis_regs (their reg_rdata is left unconnected; synthesis drops them).  SPLIT = 1 (default at
// NAXES <= 2): per axis gated copies of its own rd_vals export (the gate, axis and word, is the
// flip-flops' synchronous reset: no LUT per bit), the axes' words ORed; SPLIT = 0 (default at NAXES > 2):
// one set of copies, each taking its value from the axis rd_axis selects (a LUT per value bit).
// Flattened lx_rocon_top (branch area2): NAXES = 2 SPLIT 137 LUT fewer for 295 more flip-flops; NAXES = 4
// the same LUTs within abc's noise for 885 more flip-flops, so the default keeps the multiplexer there.
// Read path: gated copies (0 unless read) ORed.
//
// Shadow (Block.shadow): the 17 stored registers that only an accepted write changes (FAULT_MASK, DEAD_TIME, KDC, UDC, UDC_MIN, UDC_MAX, OC_THRESH, ANGLE_CAL, HALL_OFFSET, KACC, ID_REF, IQ_REF, SEG_ADDR, FW, FW_R2, IQ_HOLD, ADC_SUM_THRESH)
// are read back from a write-through block RAM {region, axis, word} instead of the axes' flip-flops:
// written (the register's read-back value of reg_wdata) in the clock of an accepted write (axis_regs.sh_we,
// the same condition under which the register takes the value; refused writes never reach it), and a
// flip-flop per axis and register, cleared by rst, records 'written since reset'; until then the read
// addresses region 0, which holds the reset values (initial contents, never written).  A read and a
// write of the same word in one clock read the old value (read-first), as the registers' copies did.
// The words: reg_addr bits 4, 3, 2, 1, 0 (the fewest that tell them apart).
// Parameters: NAXES (1..), SPLIT (read registers per axis: 1, or one set: 0; the same reg_rdata),
// AXB (axis bits, derived); VW = the width of rd_vals per axis.
// Latency: reg_rdata is valid the clock after reg_rd and 0 in every other clock (as the block's).
// Reset: synchronous (rst); read data to 0.
`default_nettype none
`include "empc_formats.vh"
module axis_rd #(
    parameter integer NAXES = 1,
    parameter integer SPLIT = (NAXES <= 2) ? 1 : 0,   // read registers per axis (1) or one set behind an rd_axis multiplexer (0)
    parameter integer AXB = (NAXES < 2) ? 1 : $clog2(NAXES)     // axis bits (derived)
) (
    input  wire                 clk,
    input  wire                 rst,
    input  wire                 reg_rd,     // read strobe (1 clock), any axis
    input  wire [AXB-1:0]       rd_axis,    // the axis read (an axis >= NAXES reads 0)
    input  wire [7:0]           reg_addr,   // word offset in the axis block
    input  wire [NAXES*295-1:0] rd_vals,    // axis a's axis_regs.rd_vals at [a*VW +: VW]
    input  wire [31:0]          reg_wdata,  // write data (the shadow RAM's)
    input  wire [NAXES*17-1:0]  sh_we,      // axis a's axis_regs.sh_we at [a*NSH +: NSH] (only axis rd_axis writes)
    input  wire [31:0]          seg_rdata,  // window read data (0 unless read), shared by the axes
    input  wire [31:0]          smem_rdata, // window read data (0 unless read), shared by the axes
    output wire [31:0]          reg_rdata   // read data, the clock after reg_rd (0 otherwise)
);
    localparam integer VW = 295;   // rd_vals bits per axis (EMPC_A_RD_VALS_W)

    localparam integer NP = 1 << AXB;
    genvar a;

    // ---------------- shadow: the stored registers, read back from a write-through block RAM
    localparam integer NSH = 17;   // shadowed registers per axis (EMPC_A_SH_N)
    localparam integer IB = 5;    // word index bits
    localparam [255:0] SH_WORDS = 256'h00000000000000000000000000000000000000000000000100000000e00fc7f0;
    wire [IB-1:0] sh_idx = {reg_addr[4], reg_addr[3], reg_addr[2], reg_addr[1], reg_addr[0]};
    wire [NP-1:0] ax_ok;              // the axes this build has
    generate for (a = 0; a < NP; a = a + 1) begin : g_axok
        assign ax_ok[a] = (a < NAXES);
    end endgenerate
    wire sh_hit = SH_WORDS[reg_addr] && ax_ok[rd_axis];
    // written since reset: one flip-flop per axis and register (set by its accepted write)
    reg  [NAXES*NSH-1:0] sh_wr;
    integer si;
    always @(posedge clk)
        for (si = 0; si < NAXES*NSH; si = si + 1)
            if (rst) sh_wr[si] <= 1'b0;
            else if (sh_we[si]) sh_wr[si] <= 1'b1;
    // the flag of (rd_axis, word): at {axis, word index}, 0 where no register is
    wire [NP*32-1:0] flv;
    generate for (a = 0; a < NP; a = a + 1) begin : g_fl
        if (a < NAXES) begin : g_ax
            assign flv[a*32 +: 32] = {sh_wr[a*NSH+15], sh_wr[a*NSH+14], sh_wr[a*NSH+13], 1'b0, 1'b0, 1'b0, 1'b0, 1'b0, 1'b0, 1'b0, 1'b0, 1'b0, sh_wr[a*NSH+12], sh_wr[a*NSH+11], sh_wr[a*NSH+10], sh_wr[a*NSH+9], sh_wr[a*NSH+8], sh_wr[a*NSH+7], 1'b0, 1'b0, 1'b0, sh_wr[a*NSH+6], sh_wr[a*NSH+5], sh_wr[a*NSH+4], sh_wr[a*NSH+3], sh_wr[a*NSH+2], sh_wr[a*NSH+1], sh_wr[a*NSH+0], 1'b0, 1'b0, 1'b0, sh_wr[a*NSH+16]};
        end else begin : g_none
            assign flv[a*32 +: 32] = 32'd0;
        end
    end endgenerate
    wire sh_fl = flv[{rd_axis, sh_idx}];
    // the written word: the register's read-back value (its fields, sign extension), per bit a table on
    // the word index (bit b of SH_PASS row b: reg_wdata[b] is stored; SH_SX<s>: bit b copies reg_wdata[s])
    localparam [32*32-1:0] SH_PASS = 1024'h4001000040010000400100004001000040010000400100004001000040010000400000004000000040010000400100004001038040010380400703c0400703c04007c3c04007c3d04007c3d04007c3d0c007c7d1c007c7d1c007c7d1c007c7d1e007c7f1e007c7f1e007c7f1e007c7f1e00fc7f1e00fc7f1e00fc7f1e00fc7f1;
    localparam [32*32-1:0] SH_SX17 = 1024'h0006000000060000000600000006000000060000000600000006000000060000000600000006000000060000000600000006000000060000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000;
    wire [31:0] sh_din;
    genvar db;
    generate for (db = 0; db < 32; db = db + 1) begin : g_din
        assign sh_din[db] = (reg_wdata[db] & SH_PASS[db*32 + sh_idx])
                          | (reg_wdata[17] & SH_SX17[db*32 + sh_idx]);
    end endgenerate
    // {region, axis, word}: region 1 written by the CPU, region 0 the reset values (never written)
    localparam integer SHW = 2 * NP * (1 << IB);
    (* ram_style = "block" *) reg [31:0] sh_mem [0:SHW-1];
    integer ri;
    initial begin
        for (ri = 0; ri < SHW; ri = ri + 1) sh_mem[ri] = 32'd0;
        for (ri = 0; ri < NP; ri = ri + 1) begin
            sh_mem[(ri << IB) + 4] = 32'h00007fff;   // FAULT_MASK
            sh_mem[(ri << IB) + 5] = 32'h00000032;   // DEAD_TIME
            sh_mem[(ri << IB) + 6] = 32'h00010000;   // KDC
            sh_mem[(ri << IB) + 7] = 32'h00000000;   // UDC
            sh_mem[(ri << IB) + 8] = 32'h00002710;   // UDC_MIN
            sh_mem[(ri << IB) + 9] = 32'h0000ea60;   // UDC_MAX
            sh_mem[(ri << IB) + 10] = 32'h00000708;   // OC_THRESH
            sh_mem[(ri << IB) + 14] = 32'h00000000;   // ANGLE_CAL
            sh_mem[(ri << IB) + 15] = 32'h00000000;   // HALL_OFFSET
            sh_mem[(ri << IB) + 16] = 32'h00000000 | (((`EMPC_KACC) & 32'h3ffff) << 0) | (((`EMPC_KACC_LOAD_SHIFT) & 32'hf) << 18) | (((`EMPC_KACC_SHIFT) & 32'h1f) << 24) | (((`EMPC_KACC_WIN) & 32'h7) << 29);   // KACC
            sh_mem[(ri << IB) + 17] = 32'h00000000;   // ID_REF
            sh_mem[(ri << IB) + 18] = 32'h00000000;   // IQ_REF
            sh_mem[(ri << IB) + 19] = 32'h00000000;   // SEG_ADDR
            sh_mem[(ri << IB) + 29] = 32'h00000000 | (((`EMPC_FW_NMAX) & 32'hff) << 0);   // FW
            sh_mem[(ri << IB) + 30] = 32'h00000000 | (((`EMPC_FW_R2_HI) & 32'hffff) << 0) | (((`EMPC_FW_R2_LO) & 32'hffff) << 16);   // FW_R2
            sh_mem[(ri << IB) + 31] = 32'h00000000 | (((`EMPC_IQ_HOLD) & 32'hfff) << 0);   // IQ_HOLD
            sh_mem[(ri << IB) + 0] = 32'h0000012c;   // ADC_SUM_THRESH
        end
    end
    reg  [31:0] sh_q;                 // 0 unless the clock after reg_rd of a shadowed word
    always @(posedge clk) begin
        if (|sh_we) sh_mem[{1'b1, rd_axis, sh_idx}] <= sh_din;
        if (rst || !(reg_rd && sh_hit)) sh_q <= 32'd0;
        else sh_q <= sh_mem[{sh_fl, rd_axis, sh_idx}];
    end

    // ---------------- read path (SPLIT: per axis; else one set behind a multiplexer on rd_axis)
    wire [31:0] q_or;                 // the copies' read word (0 unless read)
    generate if (SPLIT != 0) begin : g_split
        // each axis's gated copies of its own values (0 unless that axis's word is read: the gate is
        // the flip-flops' synchronous reset, no LUT per bit), the axes' words ORed
        wire [NAXES*32-1:0] q_ax;
        for (a = 0; a < NAXES; a = a + 1) begin : g_rd
            wire [VW-1:0] v = rd_vals[a*VW +: VW];
            wire [9:0] v_ctrl = v[9:0];
            wire [12:0] v_status = v[22:10];
            wire [14:0] v_fault = v[37:23];
            wire [11:0] v_adc_off0 = v[49:38];
            wire [11:0] v_adc_off1 = v[61:50];
            wire [11:0] v_adc_off2 = v[73:62];
            wire [31:0] v_pos = v[105:74];
            wire [15:0] v_theta = v[121:106];
            wire [23:0] v_iabc0 = v[145:122];
            wire [11:0] v_iabc1 = v[157:146];
            wire [15:0] v_latency = v[173:158];
            wire [26:0] v_adc_psum0 = v[200:174];
            wire [26:0] v_adc_psum1 = v[227:201];
            wire [26:0] v_adc_psum2 = v[254:228];
            wire [7:0] v_cnt_wr_refused = v[262:255];
            wire [7:0] v_cnt_adc_miss = v[270:263];
            wire [15:0] v_cnt_enc_err = v[286:271];
            wire [7:0] v_cnt_swap_ref = v[294:287];
            wire rd_a = reg_rd && (rd_axis == a[AXB-1:0]);

            // ---------------- read path: gated copies / shared read register, ORed
            wire rd_p0 = rd_a && (reg_addr[7:7] == 1'd0);
            reg  [9:0]   q_ctrl;
            reg  [12:0]  q_status;
            reg  [14:0]  q_fault;
            reg  [11:0]  q_adc_off0;
            reg  [11:0]  q_adc_off1;
            reg  [11:0]  q_adc_off2;
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
            reg  [7:0]   q_cnt_swap_ref;
            always @(posedge clk) begin
                q_ctrl <= (rd_p0 && reg_addr[6:0] == 7'h0) ? v_ctrl : 10'd0;
                q_status <= (rd_p0 && reg_addr[6:0] == 7'h2) ? v_status : 13'd0;
                q_fault <= (rd_p0 && reg_addr[6:0] == 7'h3) ? v_fault : 15'd0;
                q_adc_off0 <= (rd_p0 && reg_addr[6:0] == 7'hb) ? v_adc_off0 : 12'd0;
                q_adc_off1 <= (rd_p0 && reg_addr[6:0] == 7'hc) ? v_adc_off1 : 12'd0;
                q_adc_off2 <= (rd_p0 && reg_addr[6:0] == 7'hd) ? v_adc_off2 : 12'd0;
                q_pos <= (rd_p0 && reg_addr[6:0] == 7'h20) ? v_pos : 32'd0;
                q_theta <= (rd_p0 && reg_addr[6:0] == 7'h22) ? v_theta : 16'd0;
                q_iabc0 <= (rd_p0 && reg_addr[6:0] == 7'h28) ? v_iabc0 : 24'd0;
                q_iabc1 <= (rd_p0 && reg_addr[6:0] == 7'h29) ? v_iabc1 : 12'd0;
                q_latency <= (rd_p0 && reg_addr[6:0] == 7'h2a) ? v_latency : 16'd0;
                q_adc_psum0 <= (rd_p0 && reg_addr[6:0] == 7'h2c) ? v_adc_psum0 : 27'd0;
                q_adc_psum1 <= (rd_p0 && reg_addr[6:0] == 7'h2d) ? v_adc_psum1 : 27'd0;
                q_adc_psum2 <= (rd_p0 && reg_addr[6:0] == 7'h2e) ? v_adc_psum2 : 27'd0;
                q_cnt_wr_refused <= (rd_p0 && reg_addr[6:0] == 7'h2f) ? v_cnt_wr_refused : 8'd0;
                q_cnt_adc_miss <= (rd_p0 && reg_addr[6:0] == 7'h3d) ? v_cnt_adc_miss : 8'd0;
                q_cnt_enc_err <= (rd_p0 && reg_addr[6:0] == 7'h3e) ? v_cnt_enc_err : 16'd0;
                q_cnt_swap_ref <= (rd_p0 && reg_addr[6:0] == 7'h42) ? v_cnt_swap_ref : 8'd0;
                if (rst) begin
                    q_ctrl <= 10'd0;
                    q_status <= 13'd0;
                    q_fault <= 15'd0;
                    q_adc_off0 <= 12'd0;
                    q_adc_off1 <= 12'd0;
                    q_adc_off2 <= 12'd0;
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
                    q_cnt_swap_ref <= 8'd0;
                end
            end
            assign q_ax[a*32 +: 32] = {16'd0, q_ctrl[9:2], 6'd0, q_ctrl[1:0]}
                             | {19'd0, q_status}
                             | {17'd0, q_fault}
                             | {20'd0, q_adc_off0}
                             | {20'd0, q_adc_off1}
                             | {20'd0, q_adc_off2}
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
                             | {24'd0, q_cnt_swap_ref};
        end
        reg  [31:0] q_any;
        integer oi;
        always @(*) begin
            q_any = 32'd0;
            for (oi = 0; oi < NAXES; oi = oi + 1) q_any = q_any | q_ax[oi*32 +: 32];
        end
        assign q_or = q_any;
    end else begin : g_mux
        // the read axis's values: a multiplexer on the bits of rd_axis (binary, so that synthesis maps
        // four axes to one LUT6 a bit; a decoded AND-OR form came out at 2-3 LUTs a bit in the
        // flattened top), the axes beyond NAXES padded with 0; one set of gated copies
        wire [NP*VW-1:0] vp;
        for (a = 0; a < NP; a = a + 1) begin : g_pad
            if (a < NAXES) begin : g_ax
                assign vp[a*VW +: VW] = rd_vals[a*VW +: VW];
            end else begin : g_none
                assign vp[a*VW +: VW] = {VW{1'b0}};
            end
        end
        wire [VW-1:0] v = vp[rd_axis*VW +: VW];
        wire [9:0] v_ctrl = v[9:0];
        wire [12:0] v_status = v[22:10];
        wire [14:0] v_fault = v[37:23];
        wire [11:0] v_adc_off0 = v[49:38];
        wire [11:0] v_adc_off1 = v[61:50];
        wire [11:0] v_adc_off2 = v[73:62];
        wire [31:0] v_pos = v[105:74];
        wire [15:0] v_theta = v[121:106];
        wire [23:0] v_iabc0 = v[145:122];
        wire [11:0] v_iabc1 = v[157:146];
        wire [15:0] v_latency = v[173:158];
        wire [26:0] v_adc_psum0 = v[200:174];
        wire [26:0] v_adc_psum1 = v[227:201];
        wire [26:0] v_adc_psum2 = v[254:228];
        wire [7:0] v_cnt_wr_refused = v[262:255];
        wire [7:0] v_cnt_adc_miss = v[270:263];
        wire [15:0] v_cnt_enc_err = v[286:271];
        wire [7:0] v_cnt_swap_ref = v[294:287];

        // ---------------- read path: gated copies / shared read register, ORed
        wire rd_p0 = reg_rd && (reg_addr[7:7] == 1'd0);
        reg  [9:0]   q_ctrl;
        reg  [12:0]  q_status;
        reg  [14:0]  q_fault;
        reg  [11:0]  q_adc_off0;
        reg  [11:0]  q_adc_off1;
        reg  [11:0]  q_adc_off2;
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
        reg  [7:0]   q_cnt_swap_ref;
        always @(posedge clk) begin
            q_ctrl <= (rd_p0 && reg_addr[6:0] == 7'h0) ? v_ctrl : 10'd0;
            q_status <= (rd_p0 && reg_addr[6:0] == 7'h2) ? v_status : 13'd0;
            q_fault <= (rd_p0 && reg_addr[6:0] == 7'h3) ? v_fault : 15'd0;
            q_adc_off0 <= (rd_p0 && reg_addr[6:0] == 7'hb) ? v_adc_off0 : 12'd0;
            q_adc_off1 <= (rd_p0 && reg_addr[6:0] == 7'hc) ? v_adc_off1 : 12'd0;
            q_adc_off2 <= (rd_p0 && reg_addr[6:0] == 7'hd) ? v_adc_off2 : 12'd0;
            q_pos <= (rd_p0 && reg_addr[6:0] == 7'h20) ? v_pos : 32'd0;
            q_theta <= (rd_p0 && reg_addr[6:0] == 7'h22) ? v_theta : 16'd0;
            q_iabc0 <= (rd_p0 && reg_addr[6:0] == 7'h28) ? v_iabc0 : 24'd0;
            q_iabc1 <= (rd_p0 && reg_addr[6:0] == 7'h29) ? v_iabc1 : 12'd0;
            q_latency <= (rd_p0 && reg_addr[6:0] == 7'h2a) ? v_latency : 16'd0;
            q_adc_psum0 <= (rd_p0 && reg_addr[6:0] == 7'h2c) ? v_adc_psum0 : 27'd0;
            q_adc_psum1 <= (rd_p0 && reg_addr[6:0] == 7'h2d) ? v_adc_psum1 : 27'd0;
            q_adc_psum2 <= (rd_p0 && reg_addr[6:0] == 7'h2e) ? v_adc_psum2 : 27'd0;
            q_cnt_wr_refused <= (rd_p0 && reg_addr[6:0] == 7'h2f) ? v_cnt_wr_refused : 8'd0;
            q_cnt_adc_miss <= (rd_p0 && reg_addr[6:0] == 7'h3d) ? v_cnt_adc_miss : 8'd0;
            q_cnt_enc_err <= (rd_p0 && reg_addr[6:0] == 7'h3e) ? v_cnt_enc_err : 16'd0;
            q_cnt_swap_ref <= (rd_p0 && reg_addr[6:0] == 7'h42) ? v_cnt_swap_ref : 8'd0;
            if (rst) begin
                q_ctrl <= 10'd0;
                q_status <= 13'd0;
                q_fault <= 15'd0;
                q_adc_off0 <= 12'd0;
                q_adc_off1 <= 12'd0;
                q_adc_off2 <= 12'd0;
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
                q_cnt_swap_ref <= 8'd0;
            end
        end
        assign q_or = {16'd0, q_ctrl[9:2], 6'd0, q_ctrl[1:0]}
                  | {19'd0, q_status}
                  | {17'd0, q_fault}
                  | {20'd0, q_adc_off0}
                  | {20'd0, q_adc_off1}
                  | {20'd0, q_adc_off2}
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
                  | {24'd0, q_cnt_swap_ref};
    end endgenerate
    assign reg_rdata = seg_rdata
                     | smem_rdata
                     | sh_q
                     | q_or;
endmodule
`default_nettype wire
