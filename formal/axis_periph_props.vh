// axis_periph_props.vh: axis-level safety properties of rtl/axis_periph.v (issue 14; the per-axis
// module of mpc_axis and of every axis of mx_axes since issue 16), included inside axis_periph under
// FORMAL only (formal/axis_periph.sby, run by flow/formal.py).  The shared engine (sequencer, MPC
// core, ADC interface, reference generator, status memory) is outside the module: its outputs are
// free inputs in every clock (every cause, the image state, the compare values may do anything);
// the sensors are cut out (theta_valid free too).  What remains is the generated register block, the
// fault latch, pwm_center and the axis glue.  The CPU port (reg_wr/reg_addr/reg_wdata), the watchdog
// and the external (kill-path) causes are free inputs.  Every reference below is built from the
// bus and the causes, not from the state it checks.
//
//  A1  any cause that its mask (or NOMASK) lets through -> every bridge output off the next clock
//  A2  outputs never on while an effective fault is latched, nor the clock after the watchdog
//      expired (not maskable), a stale DC-link value (if dclink is unmasked) or a stalled sequencer
//  A3  outputs come back only after CMD.fault_clear in clocks where the effective causes had gone
//      (independent reference latch, and fault_ctrl's latch equals it)
//  A4  a clear with no cause and the bridges requested restarts the outputs within 2 P + 4 clocks
//  A5  complementary build: every switch turns on only after >= DEAD_TIME_MIN clocks with both
//      switches of its half-bridge off, whatever the CPU writes; DEAD_TIME >= DEAD_TIME_MIN
//  A6  the safety registers change only through an accepted write with the bridges not live;
//      FAULT_MASK only right after the unlock (reference: key write, consumed by the next write of
//      the axis, timed out at the UNLOCK_ARM-th period start)
//  A7  route_ok low (a routed build: one of the axis's phases drives no output, out_route's mapped)
//      -> every bridge output off the next clock, whatever CTRL.enable says
//  C*  covers: restart after a fault, FAULT_MASK written through the unlock
/* verilator lint_off UNUSEDSIGNAL */
    localparam integer PP = PWM_HALF_PERIOD;
    reg f_pv = 1'b0;
    always @(posedge clk) f_pv <= 1'b1;
    always @(*) if (!f_pv) assume(rst);
    always @(*) assume(!pwm_sync_in);                      // one axis: no external period restart

    wire [NCAUSE-1:0] f_m = fault_mask | NOMASK;
    wire       f_eff = |(causes & f_m);
    wire       f_off = (pwm_hi == 3'b000) && (pwm_lo == 3'b000);
    reg        p_rst, p_eff, p_wdog, p_stale, p_stall, p_dcl_m, p_live, p_wr, p_rok;
    reg [7:0]  p_addr;
    reg [31:0] p_wdata;
    reg [NCAUSE-1:0] p_mask;
    reg [`EMPC_A_DEAD_TIME_W-1:0] p_dead;
    reg [`EMPC_A_OC_THRESH_W-1:0] p_oc;
    reg [`EMPC_A_UDC_MIN_W-1:0] p_umin, p_umax;
    reg [`EMPC_A_ANGLE_CAL_W-1:0] p_acal, p_hoff;
    reg [`EMPC_A_CTRL_PWM_PER_CONTROL_W-1:0] p_ppc;
    reg [`EMPC_A_ADC_SUM_THRESH_W-1:0] p_sum;
    always @(posedge clk) begin
        p_rst <= rst;
        p_eff <= f_eff;
        p_wdog <= watchdog_expired;
        p_stale <= (udc_age == FRESH_N);
        p_stall <= seq_stall;
        p_dcl_m <= fault_mask[`EMPC_A_FAULT_DCLINK];
        p_live <= bridges_live;
        p_rok <= route_ok;
        p_wr <= reg_wr;
        p_addr <= reg_addr;
        p_wdata <= reg_wdata;
        p_mask <= fault_mask;
        p_dead <= dead_time;
        p_oc <= oc_thresh;
        p_umin <= udc_min;
        p_umax <= udc_max;
        p_acal <= angle_cal;
        p_hoff <= hall_offset;
        p_ppc <= ctrl_pwm_per_control;
        p_sum <= adc_sum_thresh;
    end
    wire f_go = f_pv && !p_rst;

    // A1, A2
    always @(*) if (f_go) begin
        if (p_eff) assert(f_off);                                          // A1
        if (|(fault_latched & f_m)) assert(f_off);                         // A2
        if (p_wdog) assert(f_off);                                         // A2: watchdog, not maskable
        if (p_stale && p_dcl_m) assert(f_off);                             // A2: stale DC-link value
        if (p_stall) assert(f_off);                                        // A2: stalled sequencer
        if (!p_rok) assert(f_off);                                         // A7: a phase unrouted
    end

    // A3: reference fault latch (the rule of the issue, independent of fault_ctrl): a cause is
    // recorded; a clear keeps exactly the causes present in its clock.  fault_ctrl must equal it,
    // and the outputs stay off while it holds an effective cause
    reg [NCAUSE-1:0] f_lat;
    always @(posedge clk) begin
        if (rst)                  f_lat <= {NCAUSE{1'b0}};
        else if (cmd_fault_clear) f_lat <= causes;
        else                      f_lat <= f_lat | causes;
    end
    always @(*) if (f_go) begin
        assert(fault_latched == f_lat);
        if (|(f_lat & f_m)) assert(f_off);
    end

    // A4: restart within 2 P + 4 clocks of a clear that left no cause, the request held
    reg [7:0] f_rc;
    wire f_hold = bridges_req && !f_eff;
    always @(posedge clk) begin
        if (rst || !f_hold)                          f_rc <= 8'd0;
        else if (cmd_fault_clear)                    f_rc <= 8'd1;
        else if (f_rc != 8'd0 && f_rc != 8'd255)     f_rc <= f_rc + 8'd1;
    end
    always @(*) if (f_go && f_rc >= 2 * PP + 4) begin
        assert(bridges_on);
        if (COMPLEMENTARY == 0) assert(pwm_lo == 3'b111);                 // PWM + enable: enables on
    end

    // A5: dead time at the pins (complementary build)
    genvar fi;
    generate if (COMPLEMENTARY != 0) begin : g_dead
        localparam integer DMIN = `EMPC_DEAD_TIME_MIN;
        always @(*) if (f_go) assert(dead_time >= DMIN);
        for (fi = 0; fi < 3; fi = fi + 1) begin : g_ch
            reg [5:0] f_offc;                       // clocks with both switches off, saturating at 63
            reg       p_h, p_l;
            always @(posedge clk) begin
                p_h <= pwm_hi[fi];
                p_l <= pwm_lo[fi];
                if (rst || pwm_hi[fi] || pwm_lo[fi]) f_offc <= 6'd0;
                else if (f_offc != 6'd63)            f_offc <= f_offc + 6'd1;
            end
            always @(*) if (f_go) begin
                assert(!(pwm_hi[fi] && pwm_lo[fi]));
                if ((pwm_hi[fi] && !p_h) || (pwm_lo[fi] && !p_l)) assert(f_offc >= DMIN);
            end
        end
    end endgenerate

    // A6: protected registers
    localparam integer AW = `EMPC_UNLOCK_ARM_W;
    localparam [AW-1:0] F_ARM = `EMPC_UNLOCK_ARM;
    reg [AW-1:0] f_arm;                             // reference unlock: ticks left
    always @(posedge clk) begin
        if (rst)          f_arm <= {AW{1'b0}};
        else if (reg_wr)  f_arm <= (reg_addr == `EMPC_A_UNLOCK && reg_wdata[15:0] == `EMPC_UNLOCK_KEY)
                                   ? F_ARM : {AW{1'b0}};
        else if (period_start && f_arm != 0) f_arm <= f_arm - 1'b1;
    end
    reg p_arm;
    always @(posedge clk) p_arm <= (f_arm != 0);
    always @(*) if (f_go) assert(unlock_armed == f_arm);                // the block's unlock = the reference
    always @(*) if (f_go) begin
        if (fault_mask != p_mask)
            assert(p_wr && p_addr == `EMPC_A_FAULT_MASK && !p_live && p_arm);
        if (dead_time != p_dead)      assert(p_wr && p_addr == `EMPC_A_DEAD_TIME && !p_live);
        if (oc_thresh != p_oc)        assert(p_wr && p_addr == `EMPC_A_OC_THRESH && !p_live);
        if (udc_min != p_umin)        assert(p_wr && p_addr == `EMPC_A_UDC_MIN && !p_live);
        if (udc_max != p_umax)        assert(p_wr && p_addr == `EMPC_A_UDC_MAX && !p_live);
        if (angle_cal != p_acal)      assert(p_wr && p_addr == `EMPC_A_ANGLE_CAL && !p_live);
        if (hall_offset != p_hoff)    assert(p_wr && p_addr == `EMPC_A_HALL_OFFSET && !p_live);
        if (adc_sum_thresh != p_sum)  assert(p_wr && p_addr == `EMPC_A_ADC_SUM_THRESH && !p_live);
        if (ctrl_pwm_per_control != p_ppc) assert(p_wr && p_addr == `EMPC_A_CTRL && !p_live);
        assert(ctrl_pwm_per_control != 0 && oc_thresh <= `EMPC_OC_THRESH_MAX && oc_thresh != 0);
    end

`ifdef AXIS_COVER
    reg f_tripped;
    always @(posedge clk) if (rst) f_tripped <= 1'b0; else if (f_eff && !f_off) f_tripped <= 1'b1;
    always @(*) if (f_go) begin
        cover(f_tripped && bridges_on && !f_off);                     // back on after a fault
        cover(fault_mask != p_mask);                                  // FAULT_MASK written through the unlock
    end
`endif
/* verilator lint_on UNUSEDSIGNAL */
