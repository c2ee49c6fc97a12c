// Generated from gen/empc/regmap.py by gen/empc/regblock.py (python -m empc.regmap --all). Do not edit.
//
// global_regs: global registers of lx_rocon_top (watchdog, time, interrupts).
//
// Write decode, stored registers with their reset values, command pulses, W1C bits and
// the read path of the registers of this block in gen/empc/regmap.py (what each register
// is and the rules: gen/empc/regblock.py, docs/registers.md).  Ports: a stored register
// or field is an output named after it, a read-only value an input of the same name.
// Read path: one shared read register (a case), plus per-register exceptions.
// Parameters: none (build-dependent reset values are empc_formats.vh macros).
// Latency: writes act in the clock after reg_wr (window strobes: combinational);
// reg_rdata is valid the clock after reg_rd and 0 in every other clock.
// Reset: synchronous (rst); stored registers to the map's reset values, pulses and read
// data to 0.
`default_nettype none
module global_regs (
    input  wire        clk,
    input  wire        rst,
    input  wire        reg_wr,                // write strobe (1 clock) for a word of this block
    input  wire        reg_rd,                // read strobe (1 clock)
    input  wire [7:0]  reg_addr,              // word offset in the block
    input  wire [31:0] reg_wdata,
    output wire [31:0] reg_rdata,             // read data, the clock after reg_rd (0 otherwise)
    input  wire [3:0]  caps_naxes,            // CAPS.naxes value
    input  wire [3:0]  caps_horizon,          // CAPS.horizon value
    input  wire [7:0]  caps_img_layout,       // CAPS.img_layout value
    input  wire [7:0]  caps_pwm_per_control,  // CAPS.pwm_per_control value
    input  wire        caps_complementary,    // CAPS.complementary value
    input  wire        caps_route,            // CAPS.route value
    input  wire [31:0] pwm_half,              // PWM_HALF value
    output reg  [31:0] scratch,               // SCRATCH (RW)
    output reg  [10:0] wdog_timeout,          // WDOG_TIMEOUT (RW)
    output reg         wdog_kick,             // WDOG_KICK: pulse when 0x5a5a is written
    input  wire [31:0] time_cnt,              // TIME value
    output reg         irq_status_period,     // IRQ_STATUS.period (W1C)
    input  wire        irq_status_period_set, // set IRQ_STATUS.period
    output reg         irq_status_fault,      // IRQ_STATUS.fault (W1C)
    input  wire        irq_status_fault_set,  // set IRQ_STATUS.fault
    output reg  [1:0]  irq_enable,            // IRQ_ENABLE (RW)
    output reg  [3:0]  out_sel0_out0,         // OUT_SEL0.out0 (RW)
    output reg  [3:0]  out_sel0_out1,         // OUT_SEL0.out1 (RW)
    output reg  [3:0]  out_sel0_out2,         // OUT_SEL0.out2 (RW)
    output reg  [3:0]  out_sel0_out3,         // OUT_SEL0.out3 (RW)
    output reg  [3:0]  out_sel0_out4,         // OUT_SEL0.out4 (RW)
    output reg  [3:0]  out_sel0_out5,         // OUT_SEL0.out5 (RW)
    output reg  [3:0]  out_sel0_out6,         // OUT_SEL0.out6 (RW)
    output reg  [3:0]  out_sel0_out7,         // OUT_SEL0.out7 (RW)
    output reg         out_sel0_wr,           // OUT_SEL0: pulse when a write is accepted
    output reg  [3:0]  out_sel1_out8,         // OUT_SEL1.out8 (RW)
    output reg  [3:0]  out_sel1_out9,         // OUT_SEL1.out9 (RW)
    output reg  [3:0]  out_sel1_out10,        // OUT_SEL1.out10 (RW)
    output reg  [3:0]  out_sel1_out11,        // OUT_SEL1.out11 (RW)
    output reg  [3:0]  out_sel1_out12,        // OUT_SEL1.out12 (RW)
    output reg  [3:0]  out_sel1_out13,        // OUT_SEL1.out13 (RW)
    output reg  [3:0]  out_sel1_out14,        // OUT_SEL1.out14 (RW)
    output reg  [3:0]  out_sel1_out15,        // OUT_SEL1.out15 (RW)
    output reg         out_sel1_wr,           // OUT_SEL1: pulse when a write is accepted
    output reg  [3:0]  adc_sel0_ax0_a,        // ADC_SEL0.ax0_a (RW)
    output reg  [3:0]  adc_sel0_ax0_b,        // ADC_SEL0.ax0_b (RW)
    output reg  [3:0]  adc_sel0_ax0_c,        // ADC_SEL0.ax0_c (RW)
    output reg  [3:0]  adc_sel0_ax1_a,        // ADC_SEL0.ax1_a (RW)
    output reg  [3:0]  adc_sel0_ax1_b,        // ADC_SEL0.ax1_b (RW)
    output reg  [3:0]  adc_sel0_ax1_c,        // ADC_SEL0.ax1_c (RW)
    output reg  [3:0]  adc_sel1_ax2_a,        // ADC_SEL1.ax2_a (RW)
    output reg  [3:0]  adc_sel1_ax2_b,        // ADC_SEL1.ax2_b (RW)
    output reg  [3:0]  adc_sel1_ax2_c,        // ADC_SEL1.ax2_c (RW)
    output reg  [3:0]  adc_sel1_ax3_a,        // ADC_SEL1.ax3_a (RW)
    output reg  [3:0]  adc_sel1_ax3_b,        // ADC_SEL1.ax3_b (RW)
    output reg  [3:0]  adc_sel1_ax3_c,        // ADC_SEL1.ax3_c (RW)
    output reg  [2:0]  in_sel_enc0,           // IN_SEL.enc0 (RW)
    output reg  [2:0]  in_sel_enc1,           // IN_SEL.enc1 (RW)
    output reg  [2:0]  in_sel_enc2,           // IN_SEL.enc2 (RW)
    output reg  [2:0]  in_sel_enc3,           // IN_SEL.enc3 (RW)
    output reg  [1:0]  in_sel_hall0,          // IN_SEL.hall0 (RW)
    output reg  [1:0]  in_sel_hall1,          // IN_SEL.hall1 (RW)
    output reg  [1:0]  in_sel_hall2,          // IN_SEL.hall2 (RW)
    output reg  [1:0]  in_sel_hall3,          // IN_SEL.hall3 (RW)
    input  wire [2:0]  route_status_mapped0,  // ROUTE_STATUS.mapped0 value
    input  wire [2:0]  route_status_mapped1,  // ROUTE_STATUS.mapped1 value
    input  wire [2:0]  route_status_mapped2,  // ROUTE_STATUS.mapped2 value
    input  wire [2:0]  route_status_mapped3,  // ROUTE_STATUS.mapped3 value
    input  wire        route_status_bad_sel,  // ROUTE_STATUS.bad_sel value
    input  wire        bridges_live,          // guard: writes to its registers are refused while high
    input  wire        route_locked,          // guard: writes to its registers are refused while high
    input  wire        wdog_unlock_tick,      // timebase of the WDOG_UNLOCK unlock (pulses)
    output wire [1:0]  wdog_unlock_armed,     // WDOG_UNLOCK unlock: ticks left, 0 = not armed (status, proofs)
    output reg         wr_refused             // pulse: a write was refused (guard, unlock or illegal value)
);
    // legal values of OUT_SEL0.out0 as a table (one LUT, no compares)
    localparam [15:0] LEGAL_OUT_SEL0_OUT0 = 16'h1fff;
    // legal values of OUT_SEL0.out1 as a table (one LUT, no compares)
    localparam [15:0] LEGAL_OUT_SEL0_OUT1 = 16'h1fff;
    // legal values of OUT_SEL0.out2 as a table (one LUT, no compares)
    localparam [15:0] LEGAL_OUT_SEL0_OUT2 = 16'h1fff;
    // legal values of OUT_SEL0.out3 as a table (one LUT, no compares)
    localparam [15:0] LEGAL_OUT_SEL0_OUT3 = 16'h1fff;
    // legal values of OUT_SEL0.out4 as a table (one LUT, no compares)
    localparam [15:0] LEGAL_OUT_SEL0_OUT4 = 16'h1fff;
    // legal values of OUT_SEL0.out5 as a table (one LUT, no compares)
    localparam [15:0] LEGAL_OUT_SEL0_OUT5 = 16'h1fff;
    // legal values of OUT_SEL0.out6 as a table (one LUT, no compares)
    localparam [15:0] LEGAL_OUT_SEL0_OUT6 = 16'h1fff;
    // legal values of OUT_SEL0.out7 as a table (one LUT, no compares)
    localparam [15:0] LEGAL_OUT_SEL0_OUT7 = 16'h1fff;
    // legal values of OUT_SEL1.out8 as a table (one LUT, no compares)
    localparam [15:0] LEGAL_OUT_SEL1_OUT8 = 16'h1fff;
    // legal values of OUT_SEL1.out9 as a table (one LUT, no compares)
    localparam [15:0] LEGAL_OUT_SEL1_OUT9 = 16'h1fff;
    // legal values of OUT_SEL1.out10 as a table (one LUT, no compares)
    localparam [15:0] LEGAL_OUT_SEL1_OUT10 = 16'h1fff;
    // legal values of OUT_SEL1.out11 as a table (one LUT, no compares)
    localparam [15:0] LEGAL_OUT_SEL1_OUT11 = 16'h1fff;
    // legal values of OUT_SEL1.out12 as a table (one LUT, no compares)
    localparam [15:0] LEGAL_OUT_SEL1_OUT12 = 16'h1fff;
    // legal values of OUT_SEL1.out13 as a table (one LUT, no compares)
    localparam [15:0] LEGAL_OUT_SEL1_OUT13 = 16'h1fff;
    // legal values of OUT_SEL1.out14 as a table (one LUT, no compares)
    localparam [15:0] LEGAL_OUT_SEL1_OUT14 = 16'h1fff;
    // legal values of OUT_SEL1.out15 as a table (one LUT, no compares)
    localparam [15:0] LEGAL_OUT_SEL1_OUT15 = 16'h1fff;

    // ---------------- write decode: one predecode per page, a case on the low bits
    wire wr_p0 = reg_wr && (reg_addr[7:5] == 3'd0);
    // unlock: WDOG_UNLOCK armed with its key until the 2th wdog_unlock_tick; the next write of the block consumes it
    reg  [1:0] unl_cnt;
    wire unl = |unl_cnt;
    assign wdog_unlock_armed = unl_cnt;
    always @(posedge clk) begin
        wdog_kick <= 1'b0;
        out_sel0_wr <= 1'b0;
        out_sel1_wr <= 1'b0;
        wr_refused <= 1'b0;
        if (rst) begin
            scratch <= 32'd0;
            wdog_timeout <= 11'd400;
            irq_status_period <= 1'd0;
            irq_status_fault <= 1'd0;
            irq_enable <= 2'd0;
            out_sel0_out0 <= 4'd1;
            out_sel0_out1 <= 4'd2;
            out_sel0_out2 <= 4'd3;
            out_sel0_out3 <= 4'd4;
            out_sel0_out4 <= 4'd5;
            out_sel0_out5 <= 4'd6;
            out_sel0_out6 <= 4'd7;
            out_sel0_out7 <= 4'd8;
            out_sel1_out8 <= 4'd9;
            out_sel1_out9 <= 4'd10;
            out_sel1_out10 <= 4'd11;
            out_sel1_out11 <= 4'd12;
            out_sel1_out12 <= 4'd0;
            out_sel1_out13 <= 4'd0;
            out_sel1_out14 <= 4'd0;
            out_sel1_out15 <= 4'd0;
            adc_sel0_ax0_a <= 4'd0;
            adc_sel0_ax0_b <= 4'd1;
            adc_sel0_ax0_c <= 4'd2;
            adc_sel0_ax1_a <= 4'd3;
            adc_sel0_ax1_b <= 4'd4;
            adc_sel0_ax1_c <= 4'd5;
            adc_sel1_ax2_a <= 4'd6;
            adc_sel1_ax2_b <= 4'd7;
            adc_sel1_ax2_c <= 4'd8;
            adc_sel1_ax3_a <= 4'd9;
            adc_sel1_ax3_b <= 4'd10;
            adc_sel1_ax3_c <= 4'd11;
            in_sel_enc0 <= 3'd0;
            in_sel_enc1 <= 3'd1;
            in_sel_enc2 <= 3'd2;
            in_sel_enc3 <= 3'd3;
            in_sel_hall0 <= 2'd0;
            in_sel_hall1 <= 2'd1;
            in_sel_hall2 <= 2'd2;
            in_sel_hall3 <= 2'd3;
            unl_cnt <= 2'd0;
        end else begin
            if (irq_status_period_set) irq_status_period <= 1'b1;
            if (irq_status_fault_set) irq_status_fault <= 1'b1;
            if (reg_wr) unl_cnt <= 2'd0;   // consumed by any write
            else if (unl && wdog_unlock_tick) unl_cnt <= unl_cnt - 1'b1;
            if (wr_p0) begin
                case (reg_addr[4:0])
                    5'h4: begin   // SCRATCH
                        scratch <= reg_wdata[31:0];
                    end
                    5'h8: begin   // WDOG_TIMEOUT
                        if (!bridges_live && unl && (reg_wdata[10:0] >= 11'd1)) begin
                            wdog_timeout <= reg_wdata[10:0];
                        end else begin
                            wr_refused <= 1'b1;
                        end
                    end
                    5'h9: begin   // WDOG_KICK
                        wdog_kick <= (reg_wdata[15:0] == 16'd23130);
                    end
                    5'hb: begin   // IRQ_STATUS
                        irq_status_period <= (irq_status_period & ~reg_wdata[0]) | irq_status_period_set;
                        irq_status_fault <= (irq_status_fault & ~reg_wdata[1]) | irq_status_fault_set;
                    end
                    5'hc: begin   // IRQ_ENABLE
                        irq_enable <= reg_wdata[1:0];
                    end
                    5'hd: begin   // WDOG_UNLOCK
                        if (reg_wdata[15:0] == 16'd49374) unl_cnt <= 2'd2;
                        else wr_refused <= 1'b1;
                    end
                    5'h10: begin   // OUT_SEL0
                        if (!route_locked && LEGAL_OUT_SEL0_OUT0[reg_wdata[3:0]] && LEGAL_OUT_SEL0_OUT1[reg_wdata[7:4]] && LEGAL_OUT_SEL0_OUT2[reg_wdata[11:8]] && LEGAL_OUT_SEL0_OUT3[reg_wdata[15:12]] && LEGAL_OUT_SEL0_OUT4[reg_wdata[19:16]] && LEGAL_OUT_SEL0_OUT5[reg_wdata[23:20]] && LEGAL_OUT_SEL0_OUT6[reg_wdata[27:24]] && LEGAL_OUT_SEL0_OUT7[reg_wdata[31:28]]) begin
                            out_sel0_out0 <= reg_wdata[3:0];
                            out_sel0_out1 <= reg_wdata[7:4];
                            out_sel0_out2 <= reg_wdata[11:8];
                            out_sel0_out3 <= reg_wdata[15:12];
                            out_sel0_out4 <= reg_wdata[19:16];
                            out_sel0_out5 <= reg_wdata[23:20];
                            out_sel0_out6 <= reg_wdata[27:24];
                            out_sel0_out7 <= reg_wdata[31:28];
                            out_sel0_wr <= 1'b1;
                        end else begin
                            wr_refused <= 1'b1;
                        end
                    end
                    5'h11: begin   // OUT_SEL1
                        if (!route_locked && LEGAL_OUT_SEL1_OUT8[reg_wdata[3:0]] && LEGAL_OUT_SEL1_OUT9[reg_wdata[7:4]] && LEGAL_OUT_SEL1_OUT10[reg_wdata[11:8]] && LEGAL_OUT_SEL1_OUT11[reg_wdata[15:12]] && LEGAL_OUT_SEL1_OUT12[reg_wdata[19:16]] && LEGAL_OUT_SEL1_OUT13[reg_wdata[23:20]] && LEGAL_OUT_SEL1_OUT14[reg_wdata[27:24]] && LEGAL_OUT_SEL1_OUT15[reg_wdata[31:28]]) begin
                            out_sel1_out8 <= reg_wdata[3:0];
                            out_sel1_out9 <= reg_wdata[7:4];
                            out_sel1_out10 <= reg_wdata[11:8];
                            out_sel1_out11 <= reg_wdata[15:12];
                            out_sel1_out12 <= reg_wdata[19:16];
                            out_sel1_out13 <= reg_wdata[23:20];
                            out_sel1_out14 <= reg_wdata[27:24];
                            out_sel1_out15 <= reg_wdata[31:28];
                            out_sel1_wr <= 1'b1;
                        end else begin
                            wr_refused <= 1'b1;
                        end
                    end
                    5'h12: begin   // ADC_SEL0
                        if (!route_locked) begin
                            adc_sel0_ax0_a <= reg_wdata[3:0];
                            adc_sel0_ax0_b <= reg_wdata[7:4];
                            adc_sel0_ax0_c <= reg_wdata[11:8];
                            adc_sel0_ax1_a <= reg_wdata[15:12];
                            adc_sel0_ax1_b <= reg_wdata[19:16];
                            adc_sel0_ax1_c <= reg_wdata[23:20];
                        end else begin
                            wr_refused <= 1'b1;
                        end
                    end
                    5'h13: begin   // ADC_SEL1
                        if (!route_locked) begin
                            adc_sel1_ax2_a <= reg_wdata[3:0];
                            adc_sel1_ax2_b <= reg_wdata[7:4];
                            adc_sel1_ax2_c <= reg_wdata[11:8];
                            adc_sel1_ax3_a <= reg_wdata[15:12];
                            adc_sel1_ax3_b <= reg_wdata[19:16];
                            adc_sel1_ax3_c <= reg_wdata[23:20];
                        end else begin
                            wr_refused <= 1'b1;
                        end
                    end
                    5'h14: begin   // IN_SEL
                        if (!route_locked) begin
                            in_sel_enc0 <= reg_wdata[2:0];
                            in_sel_enc1 <= reg_wdata[6:4];
                            in_sel_enc2 <= reg_wdata[10:8];
                            in_sel_enc3 <= reg_wdata[14:12];
                            in_sel_hall0 <= reg_wdata[17:16];
                            in_sel_hall1 <= reg_wdata[21:20];
                            in_sel_hall2 <= reg_wdata[25:24];
                            in_sel_hall3 <= reg_wdata[29:28];
                        end else begin
                            wr_refused <= 1'b1;
                        end
                    end
                    default: ;
                endcase
            end
        end
    end

    // ---------------- read path: gated copies / shared read register, ORed
    wire rd_p0 = reg_rd && (reg_addr[7:5] == 3'd0);
    reg  [31:0]  q_scratch;
    reg  [31:0]  q_mux;
    always @(posedge clk) begin
        q_scratch <= (rd_p0 && reg_addr[4:0] == 5'h4) ? scratch : 32'd0;
        if (rst || !rd_p0) begin
            q_mux <= 32'd0;
        end else begin
            case (reg_addr[4:0])
                5'h0: q_mux <= 32'h454d5043;   // ID
                5'h1: q_mux <= 32'h00010000;   // VERSION
                5'h2: q_mux <= {6'd0, caps_route, caps_complementary, caps_pwm_per_control, caps_img_layout, caps_horizon, caps_naxes};   // CAPS
                5'h3: q_mux <= pwm_half;   // PWM_HALF
                5'h8: q_mux <= {21'd0, wdog_timeout};   // WDOG_TIMEOUT
                5'ha: q_mux <= time_cnt;   // TIME
                5'hb: q_mux <= {30'd0, irq_status_fault, irq_status_period};   // IRQ_STATUS
                5'hc: q_mux <= {30'd0, irq_enable};   // IRQ_ENABLE
                5'h10: q_mux <= {out_sel0_out7, out_sel0_out6, out_sel0_out5, out_sel0_out4, out_sel0_out3, out_sel0_out2, out_sel0_out1, out_sel0_out0};   // OUT_SEL0
                5'h11: q_mux <= {out_sel1_out15, out_sel1_out14, out_sel1_out13, out_sel1_out12, out_sel1_out11, out_sel1_out10, out_sel1_out9, out_sel1_out8};   // OUT_SEL1
                5'h12: q_mux <= {8'd0, adc_sel0_ax1_c, adc_sel0_ax1_b, adc_sel0_ax1_a, adc_sel0_ax0_c, adc_sel0_ax0_b, adc_sel0_ax0_a};   // ADC_SEL0
                5'h13: q_mux <= {8'd0, adc_sel1_ax3_c, adc_sel1_ax3_b, adc_sel1_ax3_a, adc_sel1_ax2_c, adc_sel1_ax2_b, adc_sel1_ax2_a};   // ADC_SEL1
                5'h14: q_mux <= {2'd0, in_sel_hall3, 2'd0, in_sel_hall2, 2'd0, in_sel_hall1, 2'd0, in_sel_hall0, 1'd0, in_sel_enc3, 1'd0, in_sel_enc2, 1'd0, in_sel_enc1, 1'd0, in_sel_enc0};   // IN_SEL
                5'h15: q_mux <= {15'd0, route_status_bad_sel, 1'd0, route_status_mapped3, 1'd0, route_status_mapped2, 1'd0, route_status_mapped1, 1'd0, route_status_mapped0};   // ROUTE_STATUS
                default: q_mux <= 32'd0;
            endcase
        end
        if (rst) begin
            q_scratch <= 32'd0;
        end
    end
    assign reg_rdata = q_mux
                     | q_scratch;
endmodule
`default_nettype wire
