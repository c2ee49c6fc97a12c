tb/hdl/adc_spi_slave.v
tb/hdl/adc_spi_tb.v
tb/hdl/pwm_center_sync2.v
tb/hdl/mpc_core_stream.v
tb/hdl/emc_regs_tb.v
tb/hdl/quad_gen.v
tb/hdl/cosim_top.v
tb/hdl/mx_seq_tb.v
