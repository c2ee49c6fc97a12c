// Generated from gen/empc/regmap.py by gen/empc/regblock.py (python -m empc.regmap --all). Do not edit.
//
// axis_rd: the read path of NAXES axis_regs blocks (registers of one axis (mpc_axis)), shared.
//
// The CPU reads one axis at a time: one set of read registers serves every axis, each taking its
// register's value from the axis rd_axis selects among the blocks' rd_vals exports, instead of
// every axis_regs keeping its own (their reg_rdata is left unconnected; synthesis drops them).
// Read path: gated copies (0 unless read) ORed.
// Parameters: NAXES (1..), AXB (axis bits, derived); VW = the width of rd_vals per axis.
// Latency: reg_rdata is valid the clock after reg_rd and 0 in every other clock (as the block's).
// Reset: synchronous (rst); read data to 0.
`default_nettype none
module axis_rd #(
    parameter integer NAXES = 1,
    parameter integer AXB = (NAXES < 2) ? 1 : $clog2(NAXES)     // axis bits (derived)
) (
    input  wire                 clk,
    input  wire                 rst,
    input  wire                 reg_rd,     // read strobe (1 clock), any axis
    input  wire [AXB-1:0]       rd_axis,    // the axis read (an axis >= NAXES reads 0)
    input  wire [7:0]           reg_addr,   // word offset in the axis block
    input  wire [NAXES*574-1:0] rd_vals,    // axis a's axis_regs.rd_vals at [a*VW +: VW]
    input  wire [31:0]          seg_rdata,  // window read data (0 unless read), shared by the axes
    input  wire [31:0]          smem_rdata, // window read data (0 unless read), shared by the axes
    output wire [31:0]          reg_rdata   // read data, the clock after reg_rd (0 otherwise)
);
    localparam integer VW = 574;   // rd_vals bits per axis (EMPC_A_RD_VALS_W)

    // ---------------- the read axis's values: a multiplexer on the bits of rd_axis (binary, so that
    // synthesis maps four axes to one LUT6 a bit; a decoded AND-OR form came out at 2-3 LUTs a bit
    // in the flattened top), the axes beyond NAXES padded with 0
    localparam integer NP = 1 << AXB;
    wire [NP*VW-1:0] vp;
    genvar a;
    generate for (a = 0; a < NP; a = a + 1) begin : g_pad
        if (a < NAXES) begin : g_ax
            assign vp[a*VW +: VW] = rd_vals[a*VW +: VW];
        end else begin : g_none
            assign vp[a*VW +: VW] = {VW{1'b0}};
        end
    end endgenerate
    wire [VW-1:0] v = vp[rd_axis*VW +: VW];
    wire [9:0] v_ctrl = v[9:0];
    wire [12:0] v_status = v[22:10];
    wire [14:0] v_fault = v[37:23];
    wire [14:0] v_fault_mask = v[52:38];
    wire [7:0] v_dead_time = v[60:53];
    wire [17:0] v_kdc = v[78:61];
    wire [19:0] v_udc = v[98:79];
    wire [19:0] v_udc_min = v[118:99];
    wire [19:0] v_udc_max = v[138:119];
    wire [11:0] v_oc_thresh = v[150:139];
    wire [11:0] v_adc_off0 = v[162:151];
    wire [11:0] v_adc_off1 = v[174:163];
    wire [11:0] v_adc_off2 = v[186:175];
    wire [15:0] v_angle_cal = v[202:187];
    wire [15:0] v_hall_offset = v[218:203];
    wire [29:0] v_kacc = v[248:219];
    wire [17:0] v_id_ref = v[266:249];
    wire [17:0] v_iq_ref = v[284:267];
    wire [3:0] v_seg_addr = v[288:285];
    wire [7:0] v_fw = v[296:289];
    wire [31:0] v_fw_r2 = v[328:297];
    wire [11:0] v_iq_hold = v[340:329];
    wire [31:0] v_pos = v[372:341];
    wire [15:0] v_theta = v[388:373];
    wire [23:0] v_iabc0 = v[412:389];
    wire [11:0] v_iabc1 = v[424:413];
    wire [15:0] v_latency = v[440:425];
    wire [26:0] v_adc_psum0 = v[467:441];
    wire [26:0] v_adc_psum1 = v[494:468];
    wire [26:0] v_adc_psum2 = v[521:495];
    wire [7:0] v_cnt_wr_refused = v[529:522];
    wire [7:0] v_cnt_adc_miss = v[537:530];
    wire [15:0] v_cnt_enc_err = v[553:538];
    wire [11:0] v_adc_sum_thresh = v[565:554];
    wire [7:0] v_cnt_swap_ref = v[573:566];

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
        q_ctrl <= (rd_p0 && reg_addr[6:0] == 7'h0) ? v_ctrl : 10'd0;
        q_status <= (rd_p0 && reg_addr[6:0] == 7'h2) ? v_status : 13'd0;
        q_fault <= (rd_p0 && reg_addr[6:0] == 7'h3) ? v_fault : 15'd0;
        q_fault_mask <= (rd_p0 && reg_addr[6:0] == 7'h4) ? v_fault_mask : 15'd0;
        q_dead_time <= (rd_p0 && reg_addr[6:0] == 7'h5) ? v_dead_time : 8'd0;
        q_kdc <= (rd_p0 && reg_addr[6:0] == 7'h6) ? v_kdc : 18'd0;
        q_udc <= (rd_p0 && reg_addr[6:0] == 7'h7) ? v_udc : 20'd0;
        q_udc_min <= (rd_p0 && reg_addr[6:0] == 7'h8) ? v_udc_min : 20'd0;
        q_udc_max <= (rd_p0 && reg_addr[6:0] == 7'h9) ? v_udc_max : 20'd0;
        q_oc_thresh <= (rd_p0 && reg_addr[6:0] == 7'ha) ? v_oc_thresh : 12'd0;
        q_adc_off0 <= (rd_p0 && reg_addr[6:0] == 7'hb) ? v_adc_off0 : 12'd0;
        q_adc_off1 <= (rd_p0 && reg_addr[6:0] == 7'hc) ? v_adc_off1 : 12'd0;
        q_adc_off2 <= (rd_p0 && reg_addr[6:0] == 7'hd) ? v_adc_off2 : 12'd0;
        q_angle_cal <= (rd_p0 && reg_addr[6:0] == 7'he) ? v_angle_cal : 16'd0;
        q_hall_offset <= (rd_p0 && reg_addr[6:0] == 7'hf) ? v_hall_offset : 16'd0;
        q_kacc <= (rd_p0 && reg_addr[6:0] == 7'h10) ? v_kacc : 30'd0;
        q_id_ref <= (rd_p0 && reg_addr[6:0] == 7'h11) ? v_id_ref : 18'd0;
        q_iq_ref <= (rd_p0 && reg_addr[6:0] == 7'h12) ? v_iq_ref : 18'd0;
        q_seg_addr <= (rd_p0 && reg_addr[6:0] == 7'h13) ? v_seg_addr : 4'd0;
        q_fw <= (rd_p0 && reg_addr[6:0] == 7'h1d) ? v_fw : 8'd0;
        q_fw_r2 <= (rd_p0 && reg_addr[6:0] == 7'h1e) ? v_fw_r2 : 32'd0;
        q_iq_hold <= (rd_p0 && reg_addr[6:0] == 7'h1f) ? v_iq_hold : 12'd0;
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
        q_adc_sum_thresh <= (rd_p0 && reg_addr[6:0] == 7'h40) ? v_adc_sum_thresh : 12'd0;
        q_cnt_swap_ref <= (rd_p0 && reg_addr[6:0] == 7'h42) ? v_cnt_swap_ref : 8'd0;
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
endmodule
`default_nettype wire
