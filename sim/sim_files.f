sim/adc_spi_slave.v
sim/adc_spi_tb.v
sim/pwm_center_sync2.v
