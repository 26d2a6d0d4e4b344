// Runs the preview page's script in Node against a live `clmarch preview`, with the few DOM objects
// it touches stubbed: the page polls /state, asks for a coarse frame and then the full one, shows
// them with their figures, and orbits the camera on an arrow key (a new coarse and full frame).
// Usage: node page_check.js http://127.0.0.1:PORT PAGE.html
const base = process.argv[2];
const page = require("fs").readFileSync(process.argv[3], "utf8");
const code = page.slice(page.indexOf("<script>") + 8, page.indexOf("</script>"));
const elements = {};
const element = id => elements[id] || (elements[id] = {
  id, textContent: "", value: id === "views" ? "depth" : "0", style: {}, dataset: {}, src: "", max: "10",
  naturalWidth: 48, naturalHeight: 32, clientWidth: 480, clientHeight: 320, tagName: "DIV",
  listeners: {}, addEventListener(type, f) { this.listeners[type] = f; },
  getBoundingClientRect() { return { left: 0, top: 0, width: 480, height: 320 }; } });
const requests = [];
global.document = { getElementById: element };
global.window = { listeners: {}, addEventListener(type, f) { this.listeners[type] = f; } };
global.navigator = { clipboard: { writeText: t => { elements.copied = t; } } };
const realFetch = fetch;
global.fetch = url => { requests.push(url); return realFetch(base + url); };
URL.createObjectURL = () => "blob:frame";
URL.revokeObjectURL = () => {};
eval(code);
setTimeout(async () => {
  window.listeners.keydown({ key: "ArrowLeft", target: { tagName: "BODY" }, preventDefault() {} });
  setTimeout(() => {
    const frames = requests.filter(r => r.startsWith("/frame"));
    console.log(JSON.stringify({ frames: frames.length, coarse: frames.filter(f => f.includes("coarse=1")).length,
      full: frames.filter(f => f.includes("coarse=0")).length, src: elements.frame.src,
      stats: elements.stats.textContent.split("\n")[0], camera: elements.camera.textContent.split("\n")[1],
      error: elements.error.textContent }));
    const ok = frames.length >= 4 && frames.some(f => f.includes("coarse=1")) && frames.some(f => f.includes("coarse=0")) &&
      elements.frame.src === "blob:frame" && elements.stats.textContent.startsWith("48x32") &&
      !elements.camera.textContent.includes("position: [0, 1, 4]") && elements.error.textContent === "";
    process.exit(ok ? 0 : 1);
  }, 3000);
}, 3000);
